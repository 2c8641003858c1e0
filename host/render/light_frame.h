// The light's grid for transparent shadow maps (Chang & Lai TR 1688 §transparent shadows; Eisemann &
// Decoret 2006 §5): voxelized from the light, its slicing axis along the light, so each column is one shadow
// ray and its slabs are depth slices.
//   directional light: an orthographic grid of cubic voxels whose z axis is the light's direction;
//   point light: a frustum grid in the light's projective space (u = x/z, v = y/z, depth uniform in 1/z),
//   where triangles stay triangles: the mesh is mapped there (project_to_light_grid) and voxelized on an
//   identity grid.
// The grid is fitted to what can shadow what the camera sees: its columns cover the receivers (the scene's
// bounds clipped to the camera's view), its depth runs from the nearest caster in those columns to the
// farthest receiver. No more than the scene needs.
#pragma once

#include <glm/glm.hpp>

#include <cstdint>
#include <string>

#include "core/grid_spec.h"
#include "core/triangle_soup.h"
#include "render/camera_frame.h"
#include "voxr_layout.h"

namespace voxr {

struct LightFrame {
  ShadowFrame params{};  // what the kernels read
  // The grid the voxelizer runs on. Orthographic: the light-aligned affine grid over the scene's
  // anchor-relative positions. Projective: an identity grid (grid units = the projected positions).
  GridSpec grid;
  glm::vec3 light_position{0.0f};             // projective: anchor-relative
  glm::mat3 view{1.0f};                       // projective: rows are the light view's x, y, z axes
  float near_depth = 0.0f, far_depth = 0.0f;  // projective: view depths of the first and last slab faces

  bool projective() const { return params.projective != 0; }
  // Anchor-relative world point -> grid units (the kernels' sf_to_grid, on the host).
  glm::vec3 to_grid(const glm::vec3& p) const;
  // Mean world depth of a slab (orthographic: the voxel edge).
  float mean_slab_length() const {
    return projective() ? (far_depth - near_depth) / float(params.dims[2]) : params.voxel_size;
  }
  // "frustum 256 x 198 x 256, depth 3.1..9.4, 71 x 55 degrees" or "orthographic 256 x 240 x 131, voxel
  // 0.012".
  std::string describe() const;
};

// The anchor-relative bounds of what the camera can see of `scene` (the scene's box clipped to the box around
// the camera's view frustum between its near and far planes).
Bounds visible_bounds(const Bounds& scene, const CameraFrame& camera);

// Fits the light's grid: `resolution` columns along the longer side of its footprint, `resolution` slabs
// (orthographic: as many cubic voxels as the depth needs, at most 4 x resolution). The footprint is the
// receivers' columns (`receivers`: anchor-relative bounds of what the camera sees) cut down to the columns of
// the triangles that can shadow a receiver (some corner of the receivers' box lies beyond the triangle's
// plane, away from the light: a floor under everything casts nothing visible); the depth runs from the
// nearest such caster in the footprint to the farthest receiver. Receivers outside the footprint are lit.
// Throws voxr::Error when a point light lies inside the receivers' bounds (a frustum cannot see all around;
// use a directional light) or the resolution is out of range.
LightFrame fit_light_frame(const RenderLight& light, const Bounds& receivers, const TriangleSoup& casters,
                           uint32_t resolution);

// Projective frames: the soup mapped into grid units (anchor 0), triangles clipped to the near half of the
// light's view (z >= half the near depth) and culled when wholly outside one side of the grid. Material ids
// are kept; triangle order is kept for the survivors.
TriangleSoup project_to_light_grid(const TriangleSoup& soup, const LightFrame& frame);

}  // namespace voxr
