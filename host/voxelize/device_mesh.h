// A triangle mesh on the device, uploaded once and voxelized any number of times (frames, benchmark
// repeats, the surface and solid stages of one run).
#pragma once

#include <cstdint>
#include <memory>

#include "cl/cl_runtime.h"
#include "core/grid_spec.h"
#include "core/triangle_soup.h"
#include "voxelize/device_colors.h"
#include "voxelize/triangle_splitter.h"

namespace voxr {

class DeviceMesh {
 public:
  // Uploads `soup` as it is: positions as float4, triangles as uint4 (indices, material). On a CPU device the
  // buffers use the soup's (page-aligned) arrays in place: the soup must then outlive the DeviceMesh and stay
  // unchanged. Its triangles must not need splitting for the grids it is voxelized on (see upload_mesh).
  // `bounds`, when given, must contain the soup's used vertices (it saves a pass over them). Throws
  // voxr::Error beyond 2^32-1 triangles.
  DeviceMesh(ClRuntime& cl, const TriangleSoup& soup, const Bounds* bounds = nullptr);
  // A mesh built on the device (e.g. the light's mesh, render/light_frame.h): `count` triangles in
  // `triangles` (uint4: indices into `positions`, material) whose used vertices lie in `bounds`;
  // `triangles_split` input triangles were split to make it. Nothing is copied.
  DeviceMesh(cl::Buffer positions, cl::Buffer triangles, uint32_t count, const Bounds& bounds,
             uint64_t triangles_split);

  uint32_t triangle_count() const { return triangle_count_; }
  const Bounds& bounds() const { return bounds_; }  // world bounds of the input's used vertices (snap_margin)
  const glm::dvec3& anchor() const {
    return anchor_;
  }  // the soup's anchor (0 for a mesh built on the device)
  const cl::Buffer& positions() const { return positions_; }
  const cl::Buffer& triangles() const { return triangles_; }
  uint64_t triangles_split() const { return triangles_split_; }  // set by upload_mesh
  double upload_ms() const { return upload_ms_; }                // profiled transfer time
  bool in_place() const { return in_place_; }                    // the device reads the host arrays
  // The colour channel's inputs, when attached (nullptr: the mesh voxelizes white). They must describe the
  // same triangles: the soup this mesh was uploaded from, or its split pieces (soup_for_colors).
  const DeviceColors* colors() const { return colors_.get(); }
  void attach_colors(std::shared_ptr<const DeviceColors> colors) { colors_ = std::move(colors); }
  // The soup whose triangles this mesh holds: `uploaded` itself, or the split pieces upload_mesh made of it
  // (their colours interpolated by the splitter, triangle_splitter.h).
  const TriangleSoup& soup_for_colors(const TriangleSoup& uploaded) const {
    return pieces_ ? *pieces_ : uploaded;
  }

 private:
  friend std::unique_ptr<DeviceMesh> upload_split_mesh(ClRuntime&, const TriangleSoup&, const GridSpec&,
                                                       SplitCull, const Bounds*);
  cl::Buffer positions_;
  cl::Buffer triangles_;
  uint32_t triangle_count_ = 0;
  Bounds bounds_;
  glm::dvec3 anchor_{0.0};
  uint64_t triangles_split_ = 0;
  double upload_ms_ = 0.0;
  bool in_place_ = false;
  std::shared_ptr<const TriangleSoup> pieces_;  // the split soup the buffers may use in place
  std::shared_ptr<const DeviceColors> colors_;
};

// Splits the triangles too long for the exact predicates on `grid` (triangle_splitter.h, `cull` says which
// pieces may go) and uploads the result; waits for the upload. `bounds` (optional) must contain the soup's
// used vertices; the mesh keeps the input's bounds either way, so the conservative margin does not depend
// on the splitting. On a CPU device the buffers use the arrays in place: `soup` must outlive the mesh and
// stay unchanged while it is used (a deforming mesh uploads each frame's positions as a new DeviceMesh, or
// keeps one soup per frame in flight); split pieces are owned by the mesh.
DeviceMesh upload_mesh(ClRuntime& cl, const TriangleSoup& soup, const GridSpec& grid, SplitCull cull,
                       const Bounds* bounds = nullptr);
// upload_mesh's mesh when some triangle needs splitting for `grid`, else nullptr: the soup's own device mesh
// (uploaded once, shared) serves as it is.
std::unique_ptr<DeviceMesh> upload_split_mesh(ClRuntime& cl, const TriangleSoup& soup, const GridSpec& grid,
                                              SplitCull cull, const Bounds* bounds = nullptr);

}  // namespace voxr
