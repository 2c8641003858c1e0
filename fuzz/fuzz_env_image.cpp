// libFuzzer target: the environment image a scene names ("environment": {"image": ...},
// docs/scene-format.md), decoded as voxr render does: make_environment_map (render/environment_map.h) ->
// read_image (io/image_file.h: libpng, OpenEXR, stb_image) -> EnvironmentMap::from_pixels. The first input
// byte picks the extension (.png, .exr, .hdr: byte % 3), the rest is the file's content, written to a
// temporary file. voxr::Error is the expected outcome for bad input and must be one line naming the file;
// anything else (another exception, a crash, a sanitizer report, a hang, memory beyond -rss_limit_mb) is a
// finding, and so is a map made without error whose size does not match its texels or whose texels are
// negative or not finite.
#include <unistd.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>

#include "render/environment_map.h"
#include "util/error.h"

namespace {

[[noreturn]] void broken(const char* what) {
  std::fprintf(stderr, "fuzz: broken promise: %s\n", what);
  std::abort();
}

const std::filesystem::path& work_dir() {
  static const std::filesystem::path dir = [] {
    std::filesystem::path d =
        std::filesystem::temp_directory_path() / ("voxr-fuzz-env-" + std::to_string(getpid()));
    std::filesystem::create_directories(d);
    return d;
  }();
  return dir;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size == 0) return 0;
  static const char* const kExtensions[] = {".png", ".exr", ".hdr"};
  const std::filesystem::path file = work_dir() / (std::string("env") + kExtensions[data[0] % 3]);
  {
    std::ofstream out(file, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data + 1), std::streamsize(size - 1));
    if (!out) broken("cannot write the temporary image");
  }
  voxr::Environment environment;
  environment.image = file.string();
  try {
    const voxr::EnvironmentMap map = voxr::make_environment_map(environment);
    if (map.width() == 0 || map.height() == 0 || map.pixels().size() != size_t(map.width()) * map.height())
      broken("map size does not match its texels");
    for (const glm::vec4& t : map.pixels())
      if (!(std::isfinite(t.x) && std::isfinite(t.y) && std::isfinite(t.z) && t.x >= 0 && t.y >= 0 &&
            t.z >= 0))
        broken("texel negative or not finite");
  } catch (const voxr::Error& e) {
    const std::string_view message = e.what();
    if (message.find(environment.image) == std::string_view::npos)
      broken("error message does not name the file");
    if (message.find('\n') != std::string_view::npos) broken("error message spans lines");
  }
  std::filesystem::remove(file);
  return 0;
}
