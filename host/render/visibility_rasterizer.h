// Camera (and light) visibility by a kernel rasterizer, no graphics API: triangles are binned into 8x8-pixel
// tiles (kernels/raster/raster_setup.cl counts each triangle's tiles, an exclusive scan places them,
// util/expand_copies.cl writes one (triangle, tile) record per raster work item: cl/record_bins.h), and a
// consumer kernel runs once
// per record over the pixel centres the triangle covers in its tile (kernels/common/raster_coverage.h). The
// depth consumer builds the visibility buffer, one 64-bit word per pixel (voxr_layout.h: depth bits << 32 |
// triangle, 64-bit atomic min); raster_resolve.cl turns it into a SurfaceSample per pixel. Everything stays
// on the device between binning, rasterizing and resolving; buffers are kept and reused frame to frame.
#pragma once

#include <glm/glm.hpp>

#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "cl/cl_runtime.h"
#include "cl/record_bins.h"
#include "cl/scratch_buffers.h"
#include "render/camera_frame.h"
#include "voxelize/device_mesh.h"
#include "voxr_layout.h"

namespace voxr {

// The faces a RasterTarget does not draw (VOXR_CULL_* in RasterParams.cull). A front face is
// counter-clockwise as the viewer sees it, i.e. seen from outside a mesh wound counter-clockwise from
// outside; a back face is one RasterPrim marks VOXR_PRIM_BACK.
enum class FaceCull : uint32_t {
  kNone = VOXR_CULL_NONE,    // every face is drawn
  kFront = VOXR_CULL_FRONT,  // front faces are dropped: only back faces are drawn
  kBack = VOXR_CULL_BACK,    // back faces are dropped: only front faces are drawn
};

// One view to rasterize: a camera, or a light's orthographic or perspective frame.
struct RasterTarget {
  // Anchor-relative world -> clip (column-major, as CameraFrame::view_projection): the image spans x/w and
  // y/w in [-1, 1] (y/w = +1 at row 0), depths z/w in [0, 1]. Geometry with z < 0 is clipped away (the near
  // plane); a triangle wholly beyond z/w = 1 is dropped, one reaching beyond it is drawn with its depths
  // clamped to 1.
  glm::mat4 view_projection{1.0f};
  uint32_t width = 0, height = 0;   // pixels, 1 .. VOXR_RASTER_MAX_SIDE each
  uint32_t kind_mask = 7;           // bit 1 << RenderMaterial.kind of the triangles drawn
  FaceCull cull = FaceCull::kNone;  // the faces not drawn
};

// The target of a camera frame: its view_projection and size, every material kind.
RasterTarget camera_target(const CameraFrame& frame);

// The parameter block raster_setup.cl reads. Throws voxr::Error for an image side of 0 or more than
// VOXR_RASTER_MAX_SIDE pixels.
RasterParams make_raster_params(const RasterTarget& target, uint32_t triangle_count, uint32_t material_count);

// The camera block raster_resolve.cl reads.
RenderCamera make_render_camera(const CameraFrame& frame);

struct RasterStats {
  uint64_t triangles = 0;      // of the mesh
  uint64_t records = 0;        // (triangle, tile) records = raster work items, over all batches
  uint64_t batches = 0;        // expand + raster rounds the record budget asked for
  uint64_t batch_records = 0;  // records per batch (the last may hold fewer)
  double kernels_ms = 0.0;     // profiled kernel time of binning and rasterizing
  std::map<std::string, double> stage_ms;
};

// A mesh binned for one target, on the device: per triangle its clipped and snapped primitive
// (voxr_layout.h RasterPrim) and its tiles (RecordBins: counts, boxes, their scan, the current batch).
// Keep one per target (camera, light) and bin into it every frame: its buffers are reused.
class RasterBins {
 public:
  const RasterParams& params() const { return params_; }
  uint32_t width() const { return params_.width; }
  uint32_t height() const { return params_.height; }
  uint32_t triangle_count() const { return params_.triangle_count; }
  uint64_t record_count() const { return tiles_.records(); }  // all batches together
  uint64_t batch_records() const { return tiles_.batch_records(); }
  uint64_t batches() const { return tiles_.batches(); }
  const cl::Buffer& prims() const { return prims_.buffer; }  // RasterPrim per triangle

 private:
  friend class VisibilityRasterizer;
  RasterParams params_{};
  GrowingBuffer prims_;
  RecordBins tiles_;
  uint64_t record_capacity_ = 0;  // a deferred binning's records (RecordBins::scan)
};

class VisibilityRasterizer {
 public:
  // Records (8 bytes each) of one batch are kept within `record_budget_bytes`. A non-empty `stage` names
  // every kernel this rasterizer launches in the profiler (else each goes under its own name, raster_*).
  // Throws voxr::Error naming the device when it lacks cl_khr_int64_extended_atomics (the visibility
  // buffer's 64-bit atomic min).
  explicit VisibilityRasterizer(ClRuntime& cl, uint64_t record_budget_bytes = uint64_t(128) << 20,
                                std::string stage = {});

  // The programs bin, rasterize and resolve use, to build before timed work.
  std::vector<ProgramSpec> programs() const;

  // Sets up and bins the triangles of `mesh` whose material (`materials`: material_count RenderMaterial on
  // the device) has a kind in target.kind_mask; triangles with a material id >= material_count are not drawn.
  // Waits for the record total (the only readback; rasterize() may defer it, ClRuntime::counts_deferred).
  void bin(const DeviceMesh& mesh, const RasterTarget& target, const cl::Buffer& materials,
           uint32_t material_count, RasterBins& bins);
  // Calls `consume(records, count)` once per batch of expanded records (CopyRecord: triangle, tile): the
  // way a kernel of its own (with raster_coverage.h) runs over the binned pixels.
  void for_each_batch(RasterBins& bins, const std::function<void(const cl::Buffer&, uint32_t)>& consume);

  // The visibility buffer of `bins`: width * height 64-bit words, row 0 at the top (voxr_layout.h).
  void rasterize_depth(RasterBins& bins, GrowingBuffer& visibility);
  // The next depth-peeling layer (Everitt 2001, "Interactive Order-Independent Transparency"): as
  // rasterize_depth, but a pixel keeps only fragments farther than `previous` (the last layer's visibility
  // buffer of the same bins) by more than `epsilon_ulps` steps of the float depth; a pixel empty in
  // `previous` stays empty. `previous` and `visibility` must be different buffers.
  void rasterize_depth_peel(RasterBins& bins, const cl::Buffer& previous, uint32_t epsilon_ulps,
                            GrowingBuffer& visibility);
  // bin() and rasterize_depth() with bins of its own.
  void rasterize(const DeviceMesh& mesh, const RasterTarget& target, const cl::Buffer& materials,
                 uint32_t material_count, GrowingBuffer& visibility, RasterStats* stats = nullptr);

  // One SurfaceSample per pixel of `frame` (width * height, row 0 at the top) from the visibility buffer that
  // rasterize() made for camera_target(frame) and `mesh`; `vertex_normals` holds one float4 (xyz unit) per
  // vertex of the mesh (upload_vertex_normals).
  void resolve(const DeviceMesh& mesh, const cl::Buffer& vertex_normals, const CameraFrame& frame,
               const cl::Buffer& visibility, GrowingBuffer& samples);

 private:
  // bin(), with `defer` passed on to RecordBins::scan.
  void bin(const DeviceMesh& mesh, const RasterTarget& target, const cl::Buffer& materials,
           uint32_t material_count, RasterBins& bins, bool defer);

  ClRuntime& cl_;
  uint64_t record_budget_bytes_;
  std::string stage_;
  RasterBins bins_;  // rasterize()'s

  // The profiler name of a launch of `kernel`: stage_ when set.
  const std::string& stage(const std::string& kernel) const { return stage_.empty() ? kernel : stage_; }
};

// Unit vertex normals (render/vertex_normals.h) as float4 for resolve().
cl::Buffer upload_vertex_normals(ClRuntime& cl, const std::vector<glm::vec3>& normals);

}  // namespace voxr
