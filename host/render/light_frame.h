// The light's grid for transparent shadow maps (Chang & Lai TR 1688 §transparent shadows; Eisemann &
// Decoret 2006 §5): voxelized from the light, its slicing axis along the light, so each column is one shadow
// ray and its slabs are depth slices.
//   directional light: an orthographic grid of cubic voxels whose z axis is the light's direction;
//   point light: a frustum grid in the light's projective space (u = x/z, v = y/z, depth uniform in 1/z),
//   where triangles stay triangles: the mesh is mapped there and voxelized on an identity grid.
// Frames fit, project, clip and split on the device (DeviceLightFrame); fit_light_frame and
// project_to_light_grid are the host definitions its tests compare with.
// The grid is fitted to what can shadow what the camera sees: its columns cover the receivers (the scene's
// bounds clipped to the camera's view), its depth runs from the nearest caster in those columns to the
// farthest receiver. No more than the scene needs.
#pragma once

#include <glm/glm.hpp>

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "cl/cl_runtime.h"
#include "cl/scratch_buffers.h"
#include "core/grid_spec.h"
#include "core/triangle_soup.h"
#include "render/camera_frame.h"
#include "render/placement_error.h"
#include "util/error.h"
#include "voxelize/device_mesh.h"
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
  // An orthographic frame for a point light so far from the receivers that its rays are parallel to within
  // a tenth of a column (light_frame.cpp kParallelColumns): its axis is the ray to the receivers' centre.
  bool parallel_point = false;

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
// (orthographic: as many cubic voxels as the depth needs, at most 4 x resolution). A point light gets a
// frustum unless it is so far that parallel rays along its axis move no shadow by a tenth of a column
// (the largest angle of its rays to the axis x the depth from the nearest caster to the farthest receiver):
// then an orthographic grid (LightFrame::parallel_point), since a frustum's slabs, uniform in 1/depth, fall
// below float resolution as the light recedes. The footprint is the
// receivers' columns (`receivers`: anchor-relative bounds of what the camera sees) cut down to the columns of
// the triangles that can shadow a receiver (some corner of the receivers' box lies beyond the triangle's
// plane, away from the light: a floor under everything casts nothing visible); the depth runs from the
// nearest such caster in the footprint to the farthest receiver. Receivers outside the footprint are lit.
// Throws PlacementError ("light.position") when a point light lies inside the receivers' bounds or beside
// them (a frustum cannot see all around; use a directional light), voxr::Error when the resolution is out of
// range. The host reference of DeviceLightFrame::fit, which frames render with
// (tests/device_light_frame_test.cpp compares them).
LightFrame fit_light_frame(const RenderLight& light, const Bounds& receivers, const TriangleSoup& casters,
                           uint32_t resolution);

// Projective frames: the soup mapped into grid units (anchor 0), triangles clipped to the near half of the
// light's view (z >= half the near depth) and culled when wholly outside one side of the grid. Material ids
// are kept; triangle order is kept for the survivors. The host reference of DeviceLightFrame::light_mesh.
TriangleSoup project_to_light_grid(const TriangleSoup& soup, const LightFrame& frame);

// What a fitted frame depends on besides the scene's triangles: the light's position or direction (not its
// colour), the receivers and the resolution. The shadow techniques keep their frame, and what they built from
// it, while the key stays equal and the scene is unchanged.
struct LightFitKey {
  RenderLight light;
  Bounds receivers;
  uint32_t resolution = 0;
  bool operator==(const LightFitKey& o) const;
};

// The light's grid and the mesh voxelized on it, built on the device from the scene's device mesh
// (kernels/render/shadow/light_project.cl): no host pass over triangles; what the frames render with. The
// host functions above are the reference: the frame is the one fit_light_frame gives (the kernels repeat its
// float operations in its order, no contraction; a device without correctly rounded division and sqrt may
// differ in the last bit), the mesh has the triangles project_to_light_grid and split_oversized_triangles
// (SplitCull::kGrid) give, as separate corners, in another order (the voxels do not depend on it). Two host
// synchronisations: one readback of the fit's four bounds and depth, one of the light mesh's size, bounds
// and split count.
class DeviceLightFrame {
 public:
  explicit DeviceLightFrame(ClRuntime& cl);

  std::vector<ProgramSpec> programs() const;

  // fit_light_frame with `casters` on the device. Throws as fit_light_frame does.
  const LightFrame& fit(const RenderLight& light, const Bounds& receivers, const DeviceMesh& casters,
                        uint32_t resolution);
  // The mesh to voxelize on the fitted frame's grid after fit(): `casters` itself for a directional light
  // when no triangle needs splitting, else a mesh in this object's buffers (valid until the next call).
  // Throws voxr::Error beyond 2^32/3 pieces or when a triangle needs more than 16 levels of splitting.
  const DeviceMesh& light_mesh(const DeviceMesh& casters);

 private:
  ClRuntime& cl_;
  LightFrame frame_;
  GrowingBuffer reduce_, boxes_, nears_, projected_, counts_, offsets_, positions_, triangles_;
  // light_mesh's reductions read back with the scan's wait: a member, so that a throw before that wait
  // (an allocation, a launch) never leaves a read into a stack that is gone.
  std::vector<uint32_t> reduce_host_;
  std::unique_ptr<DeviceMesh> mesh_;

  // fit() with or without taking a point light as parallel; false (frame_ untouched) when the casters make a
  // parallel frame too coarse.
  bool fit_attempt(const RenderLight& light, const Bounds& receivers, const DeviceMesh& casters,
                   uint32_t resolution, bool allow_parallel);
};

}  // namespace voxr
