// libFuzzer target: the scene reader (docs/scene-format.md), JSON text -> Scene -> the world triangles a
// render or voxelize takes (scene_triangles, posed at t = 0 when animated) and their validation. voxr::Error
// is the expected outcome for bad input and must be one line starting with the scene's label; anything else
// (another exception, a crash, a sanitizer report, a hang, memory beyond -rss_limit_mb) is a finding, and
// so is a scene read without error whose camera, light or triangles are not finite. Mesh files are looked
// for in a folder that does not exist ($VOXR_MESH_DIR too), so "file" keys exercise the path errors only;
// the mesh readers have their own targets.
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <string_view>

#include "core/scene.h"
#include "util/error.h"

namespace {

[[noreturn]] void broken(const char* what) {
  std::fprintf(stderr, "fuzz: broken promise: %s\n", what);
  std::abort();
}

bool finite(const glm::dvec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  setenv("VOXR_MESH_DIR", "/nonexistent-voxr-fuzz-meshes", 1);
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string label = "fuzz.json";
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    voxr::Scene scene = voxr::parse_scene(text, label, "/nonexistent-voxr-fuzz-scenes");
    if (!finite(scene.camera.position) || !finite(scene.camera.look_at) || !finite(scene.light.position))
      broken("camera or light not finite");
    const voxr::TriangleSoup soup = voxr::take_scene_triangles(scene);
    voxr::validate_soup(soup, label);
  } catch (const voxr::Error& e) {
    const std::string_view message = e.what();
    if (message.rfind(label, 0) != 0) broken("error message does not start with the scene's label");
    if (message.find('\n') != std::string_view::npos) broken("error message spans lines");
  }
  return 0;
}
