// A triangle mesh on the device, uploaded once and voxelized any number of times (frames, benchmark
// repeats, the surface and solid stages of one run).
#pragma once

#include <cstdint>
#include <memory>

#include "cl/cl_runtime.h"
#include "core/grid_spec.h"
#include "core/triangle_soup.h"
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

  uint32_t triangle_count() const { return triangle_count_; }
  const Bounds& bounds() const { return bounds_; }  // world bounds of the input's used vertices (snap_margin)
  const cl::Buffer& positions() const { return positions_; }
  const cl::Buffer& triangles() const { return triangles_; }
  uint64_t triangles_split() const { return triangles_split_; }  // set by upload_mesh
  double upload_ms() const { return upload_ms_; }                // profiled transfer time
  bool in_place() const { return in_place_; }                    // the device reads the host arrays

 private:
  friend DeviceMesh upload_mesh(ClRuntime&, const TriangleSoup&, const GridSpec&, SplitCull, const Bounds*);
  cl::Buffer positions_;
  cl::Buffer triangles_;
  uint32_t triangle_count_ = 0;
  Bounds bounds_;
  uint64_t triangles_split_ = 0;
  double upload_ms_ = 0.0;
  bool in_place_ = false;
  std::shared_ptr<const TriangleSoup> pieces_;  // the split soup the buffers may use in place
};

// Splits the triangles too long for the exact predicates on `grid` (triangle_splitter.h, `cull` says which
// pieces may go) and uploads the result; waits for the upload. `bounds` (optional) must contain the soup's
// used vertices; the mesh keeps the input's bounds either way, so the conservative margin does not depend
// on the splitting. On a CPU device the buffers use the arrays in place: `soup` must outlive the mesh and
// stay unchanged while it is used (a deforming mesh uploads each frame's positions as a new DeviceMesh, or
// keeps one soup per frame in flight); split pieces are owned by the mesh.
DeviceMesh upload_mesh(ClRuntime& cl, const TriangleSoup& soup, const GridSpec& grid, SplitCull cull,
                       const Bounds* bounds = nullptr);

}  // namespace voxr
