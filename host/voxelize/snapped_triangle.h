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

// Bound, in 1/VOXR_SUBVOXEL voxel units (rounded up, at least 1), on how far a snapped vertex inside `bounds`
// or the grid's own box (world; the splitter may move pieces towards the grid) can lie from the exact grid
// coordinates of its input position — the position's transform by `grid` in exact arithmetic: half a unit
// from rounding to the lattice, plus the error of the float transform (16 ulp of the terms it sums, a
// generous bound). Conservative voxelization widens every voxel box by this much, so a voxel the input
// triangle touches is never lost (the widened test is a superset of the exact one: each point of the input
// triangle has a point of the snapped triangle within the bound, barycentric coordinates being the same).
uint32_t snap_margin(const GridSpec& grid, const Bounds& bounds);

// Grid-unit coordinates exactly as the kernels compute them.
glm::vec3 grid_coords(const std::array<float, 12>& world_to_grid, const glm::vec4& p);
SnappedTriangle snap_triangle(const std::array<float, 12>& world_to_grid, const TriangleSoup& soup,
                              size_t triangle);
// Fixed-point unit normal (VOXR_NORMAL_ONE per unit), bit-identical to vox_scanline.h's.
std::array<int32_t, 3> fixed_normal(const SnappedTriangle& t);

}  // namespace voxr
