// Option groups of the rendering commands (voxr-render only: they read the render library's method tables).
// See option_groups.h for the rules every group follows.
#pragma once

#include <CLI/CLI.hpp>

#include <string>

namespace voxr::cli {

// --shadows METHOD, checked while parsing (parse_shadow_method); `role` says what the method is for here,
// and the help lists every method with its summary.
CLI::Option* add_shadows_option(CLI::App& app, std::string& shadows, const std::string& role);

}  // namespace voxr::cli
