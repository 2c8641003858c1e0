#include "cli/option_groups_render.h"

#include <fmt/format.h>

#include "render/shadow_method.h"
#include "util/error.h"

namespace voxr::cli {

CLI::Option* add_shadows_option(CLI::App& app, std::string& shadows, const std::string& role) {
  std::string methods;
  for (const ShadowMethodInfo& info : kShadowMethods)
    methods += fmt::format("{}{} ({})", methods.empty() ? "" : "; ", info.name, info.summary);
  return app.add_option("--shadows", shadows, role + ": " + methods)
      ->check(CLI::Validator(
          [](std::string& name) -> std::string {
            try {
              parse_shadow_method(name);
              return "";
            } catch (const Error& e) {
              return e.what();
            }
          },
          "METHOD"));
}

}  // namespace voxr::cli
