#include "test_support.h"

#include <cstdlib>
#include <filesystem>
#include <memory>

#include <fmt/format.h>

namespace voxr::test {

namespace {
// Before any OpenCL call and before the CLI tests start the voxr binary: PoCL compiles each kernel on
// first use, and caches in the build tree (PoCL's, and voxr's program cache) let later runs reuse the
// binaries. Values already set win.
const bool kEnvironment = [] {
  setenv("POCL_CACHE_DIR", VOXR_BINARY_DIR "/pocl-cache", 0);
  setenv("VOXR_CACHE_DIR", VOXR_BINARY_DIR "/voxr-cache", 0);
  setenv("VOXR_MESH_DIR", VOXR_SOURCE_DIR "/data/meshes", 0);
  // The OpenVDB plugin (.vdb output) is beside voxr, not beside voxr_tests.
  setenv("VOXR_OPENVDB_PLUGIN", VOXR_BINARY_DIR "/libvoxr_openvdb_peer.so", 0);
  return true;
}();
}  // namespace

ClRuntime& runtime() {
  static std::unique_ptr<ClRuntime> rt = std::make_unique<ClRuntime>("");
  return *rt;
}

std::string compare_grids(const VoxelGrid& expected, const VoxelGrid& actual, float normal_tolerance) {
  if (expected.spec.dims != actual.spec.dims) return "dims differ";
  std::string report;
  size_t differences = 0;
  auto note = [&](uint64_t linear, const std::string& what) {
    if (differences++ < 8) {
      const auto& d = expected.spec.dims;
      report += fmt::format("  voxel ({}, {}, {}): {}\n", linear % d.x, (linear / d.x) % d.y,
                            linear / (uint64_t(d.x) * d.y), what);
    }
  };
  for (uint64_t w = 0; w < expected.occ.size(); ++w) {
    uint32_t diff = expected.occ[w] ^ actual.occ[w];
    while (diff) {
      const int b = __builtin_ctz(diff);
      note(w * 32 + b, (expected.occ[w] >> b) & 1 ? "missing" : "extra");
      diff &= diff - 1;
    }
  }
  if (differences == 0) {
    expected.for_each_set([&](uint64_t linear, uint64_t r) {
      if (!expected.count.empty() && expected.count[r] != actual.count.at(r))
        note(linear, fmt::format("count {} vs {}", expected.count[r], actual.count[r]));
      if (!expected.material.empty() && expected.material[r] != actual.material.at(r))
        note(linear, fmt::format("material {} vs {}", expected.material[r], actual.material[r]));
      if (!expected.color.empty() && expected.color[r] != actual.color.at(r))
        note(linear, fmt::format("color {:08x} vs {:08x}", expected.color[r], actual.color[r]));
      if (!expected.normal_sum.empty() && expected.normal_sum[r] != actual.normal_sum.at(r))
        note(linear, fmt::format("normal sum ({},{},{}) vs ({},{},{})", expected.normal_sum[r].x,
                                 expected.normal_sum[r].y, expected.normal_sum[r].z, actual.normal_sum[r].x,
                                 actual.normal_sum[r].y, actual.normal_sum[r].z));
      if (!expected.normal.empty() &&
          glm::length(expected.normal[r] - actual.normal.at(r)) > normal_tolerance)
        note(linear, "normal differs");
    });
  }
  if (differences == 0) return {};
  return fmt::format("{} differences (expected {} set voxels, got {}):\n{}", differences, expected.voxels_set,
                     actual.voxels_set, report);
}

TriangleSoup random_soup(uint32_t seed, size_t count, float lo, float hi, float max_edge) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> pos(lo, hi), off(-max_edge, max_edge);
  TriangleSoup soup;
  for (size_t t = 0; t < count; ++t) {
    const glm::vec3 a(pos(rng), pos(rng), pos(rng));
    const uint32_t base = uint32_t(soup.positions.size());
    soup.positions.push_back(glm::vec4(a, 1.0f));
    for (int c = 0; c < 2; ++c)
      soup.positions.push_back(
          glm::vec4(glm::clamp(a + glm::vec3(off(rng), off(rng), off(rng)), lo, hi), 1.0f));
    soup.triangles.push_back({base, base + 1, base + 2, uint32_t(t % 5)});
  }
  return soup;
}

GridSpec fitted(const TriangleSoup& soup, uint32_t res) {
  GridRequest r;
  r.resolution = res;
  return fit_grid(soup.bounds(), r, soup.anchor);
}

GridSpec unit_grid(glm::uvec3 dims) {
  GridSpec g;
  g.dims = dims;
  return g;
}

TriangleSoup box_soup(glm::vec3 lo, glm::vec3 hi, uint32_t material) {
  TriangleSoup s;
  for (int c = 0; c < 8; ++c)
    s.positions.push_back(glm::vec4(c & 1 ? hi.x : lo.x, c & 2 ? hi.y : lo.y, c & 4 ? hi.z : lo.z, 1.0f));
  const uint32_t faces[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                                {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& f : faces) {
    s.triangles.push_back({f[0], f[1], f[2], material});
    s.triangles.push_back({f[0], f[2], f[3], material});
  }
  return s;
}

std::string mesh_path(const std::string& name) {
  const char* dir = std::getenv("VOXR_MESH_DIR");
  const std::filesystem::path p = std::filesystem::path(dir ? dir : VOXR_SOURCE_DIR "/data/meshes") / name;
  return std::filesystem::exists(p) ? p.string() : std::string();
}

void add_square(TriangleSoup& soup, float height, float lo, float hi, uint32_t material) {
  const uint32_t b = uint32_t(soup.positions.size());
  soup.positions.push_back({lo, height, lo, 1});
  soup.positions.push_back({hi, height, lo, 1});
  soup.positions.push_back({hi, height, hi, 1});
  soup.positions.push_back({lo, height, hi, 1});
  soup.triangles.push_back({b, b + 2, b + 1, material});
  soup.triangles.push_back({b, b + 3, b + 2, material});
}

}  // namespace voxr::test
