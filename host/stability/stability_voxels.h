// What the voxelization and input stability cases share: every voxelization method by name (the Table 1
// names, host/bench/table1.h), each method's exact CPU reference, voxel set differences, and the small
// difference pictures of the page.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "cl/cl_runtime.h"
#include "core/grid_spec.h"
#include "core/triangle_soup.h"
#include "grid/voxel_grid.h"
#include "voxelize/voxelizer.h"

namespace voxr {

// table1_methods(): hybrid-conservative, slice-conservative, slice-center, grid (conservative),
// slicemap-uniform, slicemap-local.
const std::vector<std::string>& stability_methods();
// Whether `method` keeps every voxel its triangles touch (the conservative rule) rather than sampling
// centres.
bool is_conservative_method(const std::string& method);

// One Voxelizer for a case, running methods by name (occupancy only).
class MethodRunner {
 public:
  explicit MethodRunner(ClRuntime& cl) : voxelizer_(cl) {}
  VoxelGrid run(const std::string& method, const TriangleSoup& soup, const GridSpec& grid);

 private:
  Voxelizer voxelizer_;
};

// The exact CPU reference of `method`'s own rule on the same snapped vertices (reference_voxelizer.h for the
// slice family, reference_slicemap.h for slicemaps): a correct kernel matches it voxel for voxel.
VoxelGrid method_reference(const std::string& method, const TriangleSoup& soup, const GridSpec& grid);

// Voxels set in `reference` and not in `result` (both on the same dims).
uint64_t missing_voxels(const VoxelGrid& result, const VoxelGrid& reference);
// Voxels set in exactly one of the two (same dims).
uint64_t differing_voxels(const VoxelGrid& a, const VoxelGrid& b);

// `soup` with every position transformed by `transform` (world, in double), anchored afresh at its bounds.
TriangleSoup transformed_soup(const TriangleSoup& soup, const glm::dmat4& transform);

// Writes a small PNG under `dir` (created) named `name`.png: the projection of `result` and `reference` along
// the grid's z, one square block per column: grey where they agree on set voxels, red where `result` has
// extra voxels, blue where it misses some, white where both are empty. Returns the file name, or "" when
// `dir` is empty.
std::string write_difference_picture(const VoxelGrid& result, const VoxelGrid& reference,
                                     const std::filesystem::path& dir, const std::string& name);

}  // namespace voxr
