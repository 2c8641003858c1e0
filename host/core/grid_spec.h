// Where the voxel grid sits in the world: an orthonormal frame (the slicing axis is the frame's z), the
// world position of the grid's corner, the voxel edge length and the integer dimensions. Voxel (i,j,k) is
// the closed box [i,i+1]x[j,j+1]x[k,k+1] in grid units; linear index = (k*dims.y + j)*dims.x + i, 64-bit.
#pragma once

#include <glm/glm.hpp>

#include <array>
#include <cstdint>
#include <optional>

#include "core/triangle_soup.h"

namespace voxr {

struct GridSpec {
  glm::mat3 axes{1.0f};    // columns: the grid's x, y, z axes in world space (orthonormal)
  glm::vec3 origin{0.0f};  // position of the grid's corner (0,0,0) relative to `anchor`
  glm::dvec3 anchor{0.0};  // world position of the frame origin and the soup's positions are in

  float voxel_size = 1.0f;
  glm::uvec3 dims{1, 1, 1};

  uint64_t voxel_count() const { return uint64_t(dims.x) * dims.y * dims.z; }
  uint64_t linear_index(uint32_t i, uint32_t j, uint32_t k) const {
    return (uint64_t(k) * dims.y + j) * dims.x + i;
  }
  // Anchor-relative position -> grid units, as the rows of a 3x4 affine matrix (the form the kernels read).
  std::array<float, 12> world_to_grid() const;
  glm::vec3 to_grid(const glm::vec3& world) const;
  // Centre of voxel (i,j,k) relative to the anchor, and in world coordinates (double, for file headers).
  glm::vec3 voxel_center_world(uint32_t i, uint32_t j, uint32_t k) const;
  glm::dvec3 voxel_center_absolute(uint32_t i, uint32_t j, uint32_t k) const;
};

// A world-space box in double precision (--bounds, a scene's grid bounds).
struct WorldBox {
  glm::dvec3 lo{0.0}, hi{0.0};
  WorldBox() = default;
  WorldBox(const glm::dvec3& l, const glm::dvec3& h) : lo(l), hi(h) {}
  WorldBox(const Bounds& b) : lo(b.lo), hi(b.hi) {}  // NOLINT: a float box is a world box too
};

// How the user asked for the grid. Exactly one of `resolution` and `dims` is used; `bounds` defaults to
// the scene bounds grown by a margin.
struct GridRequest {
  uint32_t resolution = 256;       // voxels along the longest axis of the bounds
  std::optional<glm::uvec3> dims;  // exact dimensions; voxels stay cubes, the bounds grow to fit
  std::optional<WorldBox> bounds;  // world box to voxelize, exactly
  // Margin around fitted bounds, in voxels. A quarter voxel puts the faces of a mesh's bounding box a quarter
  // voxel from voxel faces and voxel centres alike, so neither the tie rules of conservative voxelization
  // nor those of the solid's centre sampling decide where a box-shaped mesh ends.
  float margin_voxels = 0.25f;
};

// Largest dimension along one axis; 64-bit indices keep 2048^3 and beyond addressable.
constexpr uint32_t kMaxGridDim = 16384;

// Fits an axis-aligned grid of cubic voxels to `scene_bounds` (relative to `anchor`, as a soup's bounds are)
// as `request` says. Fitted grids are centred on the bounds with `margin_voxels` around them, except that an
// axis whose bounding faces would then fall within 1/8 voxel of a voxel face or centre is shifted to keep
// both faces at least 1/8 voxel (up to 1/4) from either. Exact bounds (request.bounds, world) are used
// as given. The result's anchor is `anchor`. Throws voxr::Error for empty bounds, zero or absurd sizes.
GridSpec fit_grid(const Bounds& scene_bounds, const GridRequest& request,
                  const glm::dvec3& anchor = glm::dvec3(0.0));

}  // namespace voxr
