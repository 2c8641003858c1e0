#include "render/visibility_rasterizer.h"

#include <glm/gtc/type_ptr.hpp>

#include <algorithm>
#include <cstring>
#include <utility>

namespace voxr {

namespace {

constexpr size_t kGroup = 256;

Defines raster_defines() {
  return {{"WG_SIZE", std::to_string(kGroup)}};
}

}  // namespace

RasterTarget camera_target(const CameraFrame& frame) {
  RasterTarget target;
  target.view_projection = frame.view_projection();
  target.width = frame.width;
  target.height = frame.height;
  return target;
}

RasterParams make_raster_params(const RasterTarget& target, uint32_t triangle_count,
                                uint32_t material_count) {
  if (target.width == 0 || target.height == 0 || target.width > VOXR_RASTER_MAX_SIDE ||
      target.height > VOXR_RASTER_MAX_SIDE)
    fail("raster image {}x{}: each side must be 1 to {} pixels", target.width, target.height,
         VOXR_RASTER_MAX_SIDE);
  RasterParams p{};
  std::memcpy(p.view_projection, glm::value_ptr(target.view_projection), sizeof(p.view_projection));
  p.width = target.width;
  p.height = target.height;
  p.kind_mask = target.kind_mask;
  p.cull = uint32_t(target.cull);
  p.triangle_count = triangle_count;
  p.material_count = material_count;
  // Screen x = (x/w + 1) width / 2 stays within +-VOXR_RASTER_GUARD pixels when |x/w| <= 2 GUARD / width - 1.
  p.guard[0] = 2.0f * float(VOXR_RASTER_GUARD) / float(target.width) - 1.0f;
  p.guard[1] = 2.0f * float(VOXR_RASTER_GUARD) / float(target.height) - 1.0f;
  return p;
}

RenderCamera make_render_camera(const CameraFrame& frame) {
  RenderCamera c{};
  for (int a = 0; a < 3; ++a) {
    c.eye[a] = frame.eye[a];
    c.forward[a] = frame.forward[a];
    c.right[a] = frame.right[a];
    c.up[a] = frame.up[a];
  }
  c.width = frame.width;
  c.height = frame.height;
  c.tan_half_fov_y = frame.tan_half_fov_y;
  c.aspect = frame.aspect();
  return c;
}

VisibilityRasterizer::VisibilityRasterizer(ClRuntime& cl, uint64_t record_budget_bytes, std::string stage)
    : cl_(cl), record_budget_bytes_(record_budget_bytes), stage_(std::move(stage)) {
  if (cl_.device().extensions.find("cl_khr_int64_extended_atomics") == std::string::npos)
    fail("{} lacks cl_khr_int64_extended_atomics, which the visibility buffer's 64-bit atomic min needs",
         cl_.device().label());
}

std::vector<ProgramSpec> VisibilityRasterizer::programs() const {
  std::vector<ProgramSpec> specs = RecordBins::programs();
  for (const char* file : {"raster_setup.cl", "raster_depth.cl", "raster_resolve.cl"})
    specs.push_back({file, raster_defines()});
  return specs;
}

void VisibilityRasterizer::bin(const DeviceMesh& mesh, const RasterTarget& target,
                               const cl::Buffer& materials, uint32_t material_count, RasterBins& bins) {
  bin(mesh, target, materials, material_count, bins, false);
}

void VisibilityRasterizer::bin(const DeviceMesh& mesh, const RasterTarget& target,
                               const cl::Buffer& materials, uint32_t material_count, RasterBins& bins,
                               bool defer) {
  const uint32_t tris = mesh.triangle_count();
  bins.params_ = make_raster_params(target, tris, material_count);
  cl::Buffer& prims = bins.prims_.ensure(cl_, uint64_t(tris) * sizeof(RasterPrim), "raster primitives");
  bins.tiles_.prepare(cl_, tris);
  if (tris == 0) return;
  cl::Kernel setup = cl_.kernel("raster_setup.cl", "raster_setup", raster_defines());
  cl_.launch(stage("raster_setup"), setup, tris, kGroup, bins.params_, mesh.positions(), mesh.triangles(),
             materials, prims, bins.tiles_.counts(), bins.tiles_.boxes());
  bins.tiles_.scan(cl_, record_budget_bytes_, stage("raster_scan"), defer ? &bins.record_capacity_ : nullptr);
}

void VisibilityRasterizer::for_each_batch(RasterBins& bins,
                                          const std::function<void(const cl::Buffer&, uint32_t)>& consume) {
  bins.tiles_.for_each_batch(cl_, stage("raster_expand"), consume);
}

void VisibilityRasterizer::rasterize_depth(RasterBins& bins, GrowingBuffer& visibility) {
  const uint32_t width = bins.width(), height = bins.height();
  const uint64_t pixels = uint64_t(width) * height;
  cl::Buffer& words = visibility.ensure(cl_, pixels * 8, "the visibility buffer");
  cl::Kernel clear = cl_.kernel("raster_depth.cl", "raster_clear", raster_defines());
  cl_.launch(stage("raster_clear"), clear, pixels, kGroup, words, cl_uint(pixels));
  cl::Kernel depth = cl_.kernel("raster_depth.cl", "raster_depth", raster_defines());
  for_each_batch(bins, [&](const cl::Buffer& records, uint32_t count) {
    cl_.launch(stage("raster_depth"), depth, count, kGroup, cl_uint(width), cl_uint(height), bins.prims(),
               records, bins.tiles_.window_records(), words);
  });
}

void VisibilityRasterizer::rasterize_depth_peel(RasterBins& bins, const cl::Buffer& previous,
                                                uint32_t epsilon_ulps, GrowingBuffer& visibility) {
  const uint32_t width = bins.width(), height = bins.height();
  const uint64_t pixels = uint64_t(width) * height;
  cl::Buffer& words = visibility.ensure(cl_, pixels * 8, "the peeled visibility buffer");
  VOXR_CHECK(words() != previous());
  cl::Kernel clear = cl_.kernel("raster_depth.cl", "raster_clear", raster_defines());
  cl_.launch(stage("raster_clear"), clear, pixels, kGroup, words, cl_uint(pixels));
  cl::Kernel peel = cl_.kernel("raster_depth.cl", "raster_depth_peel", raster_defines());
  for_each_batch(bins, [&](const cl::Buffer& records, uint32_t count) {
    cl_.launch(stage("raster_depth_peel"), peel, count, kGroup, cl_uint(width), cl_uint(height), bins.prims(),
               records, bins.tiles_.window_records(), previous, cl_uint(epsilon_ulps), words);
  });
}

void VisibilityRasterizer::rasterize(const DeviceMesh& mesh, const RasterTarget& target,
                                     const cl::Buffer& materials, uint32_t material_count,
                                     GrowingBuffer& visibility, RasterStats* stats) {
  std::map<std::string, Profiler::Stat> before;
  if (stats) {
    cl_.finish();
    before = cl_.profiler().stats();
  }
  // Only the depth kernel, which reads the true record count on the device, consumes these bins: their
  // total may travel with a later wait when the caller defers counts and wants no exact stats.
  bin(mesh, target, materials, material_count, bins_, stats == nullptr);
  rasterize_depth(bins_, visibility);
  if (stats) {
    cl_.finish("rasterizing");
    const Profiler::Split split = cl_.profiler().since(before);
    stats->triangles = mesh.triangle_count();
    stats->records = bins_.record_count();
    stats->batches = bins_.batches();
    stats->batch_records = bins_.batch_records();
    stats->kernels_ms = split.kernels_ms;
    stats->stage_ms = split.stage_ms;
  }
}

void VisibilityRasterizer::resolve(const DeviceMesh& mesh, const cl::Buffer& vertex_normals,
                                   const CameraFrame& frame, const cl::Buffer& visibility,
                                   GrowingBuffer& samples) {
  const uint64_t pixels = uint64_t(frame.width) * frame.height;
  VOXR_CHECK(frame.width <= VOXR_RASTER_MAX_SIDE && frame.height <= VOXR_RASTER_MAX_SIDE);
  cl::Buffer& out = samples.ensure(cl_, pixels * sizeof(SurfaceSample), "the surface samples");
  cl::Kernel resolve = cl_.kernel("raster_resolve.cl", "raster_resolve", raster_defines());
  cl_.launch(stage("raster_resolve"), resolve, pixels, kGroup, make_render_camera(frame), visibility,
             mesh.positions(), mesh.triangles(), vertex_normals, cl_uint(mesh.triangle_count()), out);
}

cl::Buffer upload_vertex_normals(ClRuntime& cl, const std::vector<glm::vec3>& normals) {
  std::vector<glm::vec4> padded(normals.size());
  for (size_t i = 0; i < normals.size(); ++i) padded[i] = glm::vec4(normals[i], 0.0f);
  const uint64_t bytes = padded.size() * sizeof(glm::vec4);
  cl::Buffer buffer = cl.buffer(bytes, "vertex normals", CL_MEM_READ_ONLY);
  cl.upload(buffer, padded.data(), bytes, "upload vertex normals");  // blocking: `padded` may go
  return buffer;
}

}  // namespace voxr
