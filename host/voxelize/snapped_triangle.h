// The host's mirror of kernels/vox_triangle.h: a triangle transformed to grid units with the kernels'
// float operations (same order, no contraction) and snapped to the 1/VOXR_SUBVOXEL lattice, plus its
// fixed-point unit normal. The CPU reference and the triangle splitter use it.
#pragma once

#include <array>
#include <cstdint>

#include "core/grid_spec.h"
#include "core/triangle_soup.h"
#include "voxr_layout.h"

namespace voxr {

struct SnappedTriangle {
  std::array<std::array<int64_t, 3>, 3> v{};  // v[vertex][axis], fixed point
  std::array<int64_t, 3> n{};                 // (v1-v0) x (v2-v0)
  uint32_t material = 0;
};

// Grid-unit coordinates exactly as the kernels compute them.
glm::vec3 grid_coords(const std::array<float, 12>& world_to_grid, const glm::vec4& p);
SnappedTriangle snap_triangle(const std::array<float, 12>& world_to_grid, const TriangleSoup& soup,
                              size_t triangle);
// Fixed-point unit normal (VOXR_NORMAL_ONE per unit), bit-identical to vox_scanline.h's.
std::array<int32_t, 3> fixed_normal(const SnappedTriangle& t);

}  // namespace voxr
