// Shared helpers for the kernel tests: one OpenCL runtime per process (PoCL in CI), exact grid comparison
// with readable diffs, and fixed-seed random triangle soups.
#pragma once

#include <gtest/gtest.h>

#include <cstdint>
#include <random>
#include <string>

#include "cl/cl_runtime.h"
#include "core/triangle_soup.h"
#include "voxelize/voxel_grid.h"

namespace voxr::test {

// The runtime on $VOXR_DEVICE or the default device, created on first use.
ClRuntime& runtime();

// Empty string when equal; otherwise the number of differing voxels and the first few, with channel.
std::string compare_grids(const VoxelGrid& expected, const VoxelGrid& actual, float normal_tolerance = 1e-5f);

// `count` triangles with vertices uniform in [lo, hi]^3 and edge lengths up to `max_edge`.
TriangleSoup random_soup(uint32_t seed, size_t count, float lo, float hi, float max_edge);

// Axis-aligned box as 12 triangles (outward winding).
TriangleSoup box_soup(glm::vec3 lo, glm::vec3 hi, uint32_t material = 0);

// Mesh from $VOXR_MESH_DIR (scripts/fetch-meshes.sh), or an empty path when absent.
std::string mesh_path(const std::string& name);

}  // namespace voxr::test
