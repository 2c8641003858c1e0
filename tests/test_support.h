// Shared helpers for the kernel tests: one OpenCL runtime per process (PoCL in CI), exact grid comparison
// with readable diffs, and fixed-seed random triangle soups.
#pragma once

#include <gtest/gtest.h>

#include <unistd.h>

#include <atomic>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>
#include <random>
#include <set>
#include <string>

#include "cl/cl_runtime.h"
#include "core/grid_spec.h"
#include "core/triangle_soup.h"
#include "grid/voxel_grid.h"

namespace voxr::test {

namespace fs = std::filesystem;

// The runtime on $VOXR_DEVICE or the default device, created on first use.
ClRuntime& runtime();

// Empty string when equal; otherwise the number of differing voxels and the first few, with channel.
std::string compare_grids(const VoxelGrid& expected, const VoxelGrid& actual, float normal_tolerance = 1e-5f);

// `count` triangles with vertices uniform in [lo, hi]^3 and edge lengths up to `max_edge`.
TriangleSoup random_soup(uint32_t seed, size_t count, float lo, float hi, float max_edge);

// The grid `voxr voxelize --res res` fits to the soup.
GridSpec fitted(const TriangleSoup& soup, uint32_t res);

// Grid units = world units: voxel (i, j, k) is [i, i+1] x [j, j+1] x [k, k+1].
GridSpec unit_grid(glm::uvec3 dims);

// Axis-aligned box as 12 triangles (outward winding).
TriangleSoup box_soup(glm::vec3 lo, glm::vec3 hi, uint32_t material = 0);

// Appends the square [lo, hi] x [lo, hi] in the plane y = height (x, z), two triangles sharing a diagonal,
// facing +y.
void add_square(TriangleSoup& soup, float height, float lo, float hi, uint32_t material);

// Sets (or, with nullopt, unsets) an environment variable for the scope of a test.
class ScopedEnv {
 public:
  ScopedEnv(const char* name, std::optional<std::string> value) : name_(name) {
    if (const char* old = std::getenv(name)) old_ = old;
    if (value)
      setenv(name, value->c_str(), 1);
    else
      unsetenv(name);
  }
  ~ScopedEnv() {
    if (old_)
      setenv(name_, old_->c_str(), 1);
    else
      unsetenv(name_);
  }
  ScopedEnv(const ScopedEnv&) = delete;
  ScopedEnv& operator=(const ScopedEnv&) = delete;

 private:
  const char* name_;
  std::optional<std::string> old_;
};

// A fresh folder per test (or per object), removed afterwards.
class TempDir {
 public:
  TempDir() {
    static std::atomic<int> counter{0};
    path_ = fs::temp_directory_path() /
            ("voxr-test-" + std::to_string(getpid()) + "-" + std::to_string(counter++));
    fs::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ec;
    fs::permissions(path_, fs::perms::owner_all, ec);  // a test may have made it read-only
    fs::remove_all(path_, ec);
  }
  fs::path write(const std::string& name, const std::string& content) const {
    const fs::path p = path_ / name;
    fs::create_directories(p.parent_path());
    std::ofstream(p, std::ios::binary) << content;
    return p;
  }
  const fs::path& path() const { return path_; }

 private:
  fs::path path_;
};

// The names of the entries in `dir` (not recursive).
inline std::set<std::string> listing(const fs::path& dir) {
  std::set<std::string> names;
  for (const auto& e : fs::directory_iterator(dir)) names.insert(e.path().filename().string());
  return names;
}

// Mesh from $VOXR_MESH_DIR (scripts/fetch-meshes.sh), or an empty path when absent.
std::string mesh_path(const std::string& name);

}  // namespace voxr::test
