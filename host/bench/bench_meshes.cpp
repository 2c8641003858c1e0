#include "bench/bench_meshes.h"

#include <cstdlib>
#include <filesystem>

#include "core/generators.h"
#include "core/mesh_loader.h"
#include "core/subdivide.h"
#include "util/error.h"

namespace voxr {

namespace {

std::filesystem::path mesh_dir() {
  const char* dir = std::getenv("VOXR_MESH_DIR");
  return dir && *dir ? std::filesystem::path(dir) : std::filesystem::path("data/meshes");
}

TriangleSoup load_packaged(const std::string& file) {
  const std::filesystem::path path = mesh_dir() / file;
  if (!std::filesystem::exists(path))
    fail("{}: not found; run scripts/fetch-meshes.sh (or set VOXR_MESH_DIR)", path.string());
  return load_mesh(path);
}

TriangleSoup base_mesh(const std::string& base) {
  if (base == "torus") return make_torus();
  if (base == "sphere") return make_uv_sphere(1.0f, 64, 128);
  if (base == "holed-sphere") {
    // Four single-triangle holes about 0.025 wide (sub-voxel up to ~80 voxels across): not watertight.
    TriangleSoup s = make_uv_sphere(1.0f, 128, 256);
    for (size_t k = 0; k < 4; ++k)
      s.triangles.erase(s.triangles.begin() + long(s.triangles.size() * (2 * k + 1) / 9));
    return s;
  }
  if (base == "bunny") return load_packaged("bunny.obj");
  if (base == "armadillo") return load_packaged("armadillo.off");
  if (base == "dragon") return load_packaged("ChineseDragon-10kv.off");
  if (base == "elephant") return load_packaged("refined_elephant.off");
  if (base == "shark") return load_packaged("mech-holes-shark.off");
  fail(
      "unknown benchmark mesh '{}' (torus, sphere, bunny, armadillo, dragon, elephant; append xN to "
      "subdivide)",
      base);
}

}  // namespace

BenchMesh make_bench_mesh(const std::string& name) {
  const size_t x = name.rfind('x');
  std::string base = name;
  int levels = 0;
  if (x != std::string::npos && x + 1 < name.size() &&
      std::isdigit(static_cast<unsigned char>(name[x + 1]))) {
    base = name.substr(0, x);
    const long factor = std::strtol(name.c_str() + x + 1, nullptr, 10);
    long f = 1;
    while (f < factor) {
      f *= 4;
      ++levels;
    }
    if (f != factor) fail("benchmark mesh '{}': the subdivision factor must be a power of 4", name);
  }
  TriangleSoup soup = base_mesh(base);
  if (levels) soup = subdivide_midpoint(soup, levels);
  return {name, std::move(soup)};
}

const std::vector<std::string>& default_bench_meshes() {
  static const std::vector<std::string> names = {"torus",       "bunny",    "armadillo",   "bunnyx4",
                                                 "armadillox4", "bunnyx16", "armadillox16"};
  return names;
}

void color_by_position(TriangleSoup& soup) {
  const Bounds b = soup.bounds();
  const glm::vec3 size = glm::max(b.size(), glm::vec3(1e-30f));
  soup.colors.vertex_rgba.clear();
  soup.colors.vertex_rgba.reserve(soup.positions.size());
  for (const glm::vec4& p : soup.positions) {
    const glm::vec3 t = glm::clamp((glm::vec3(p) - b.lo) / size, 0.0f, 1.0f) * 255.0f + 0.5f;
    soup.colors.vertex_rgba.push_back(uint32_t(t.x) | (uint32_t(t.y) << 8) | (uint32_t(t.z) << 16) |
                                      0xff000000u);
  }
}

}  // namespace voxr
