// Google Benchmark of the kernel rasterizer, the per-frame case: a mesh uploaded once, then bin + rasterize
// (visibility buffer) + resolve (SurfaceSample per pixel) of a 640x480 camera frame again and again, all on
// the device. Times are the device's profiling events (UseManualTime); wall_ms adds the host's waits (the
// scan total is read back once per frame). Counters break a frame into its kernels.
#include <benchmark/benchmark.h>

#include <map>

#include "bench_runtime.h"
#include "cl/cl_runtime.h"
#include "core/generators.h"
#include "render/vertex_normals.h"
#include "render/visibility_rasterizer.h"
#include "util/clock.h"

namespace voxr {
namespace {

// ~65K triangles: 2 per leaf (kTreeLeavesPerDensity leaves per unit density) plus the trunk.
constexpr float kTreeDensity = 108.0f;

CameraFrame frame_looking_at(glm::vec3 eye, glm::vec3 target) {
  CameraFrame f;
  f.eye = eye;
  f.forward = glm::normalize(target - eye);
  f.right = glm::normalize(glm::cross(f.forward, glm::vec3(0, 1, 0)));
  f.up = glm::cross(f.right, f.forward);
  f.tan_half_fov_y = 0.41421356f;  // 45 degrees
  f.width = 640;
  f.height = 480;
  f.near_plane = 0.05f;
  f.far_plane = 20.0f;
  return f;
}

void raster_frame(benchmark::State& state, const TriangleSoup& soup, const CameraFrame& frame) {
  ClRuntime& cl = bench_runtime();
  const DeviceMesh mesh(cl, soup);
  RenderMaterial opaque{};
  RenderMaterial sheet{};
  sheet.kind = VOXR_MATERIAL_SHEET;
  const RenderMaterial host_materials[2] = {opaque, sheet};
  cl::Buffer materials = cl.buffer(sizeof(host_materials), "materials");
  cl.upload(materials, host_materials, sizeof(host_materials), "upload materials");
  const cl::Buffer normals = upload_vertex_normals(cl, vertex_normals(soup));
  VisibilityRasterizer raster(cl);
  cl.build_programs(raster.programs());
  const RasterTarget target = camera_target(frame);
  GrowingBuffer visibility, samples;
  std::map<std::string, double> stage_sum;
  double wall_sum = 0.0;
  RasterStats stats;
  for (auto _ : state) {
    cl.finish();
    const auto before = cl.profiler().stats();
    const auto start = Clock::now();
    raster.rasterize(mesh, target, materials, 2, visibility);
    raster.resolve(mesh, normals, frame, visibility.buffer, samples);
    cl.finish("raster frame");
    wall_sum += ms_since(start);
    const Profiler::Split split = cl.profiler().since(before);
    state.SetIterationTime(split.kernels_ms * 1e-3);
    for (const auto& [stage, ms] : split.stage_ms) stage_sum[stage] += ms;
  }
  raster.rasterize(mesh, target, materials, 2, visibility, &stats);
  const double n = double(state.iterations());
  for (const auto& [stage, ms] : stage_sum) state.counters[stage + "_ms"] = ms / n;
  state.counters["wall_ms"] = wall_sum / n;
  state.counters["triangles"] = double(stats.triangles);
  state.counters["records"] = double(stats.records);
  state.counters["tri/s"] = benchmark::Counter(double(stats.triangles) * n, benchmark::Counter::kIsRate);
  state.SetLabel(cl.device().name);
}

void BM_RasterTree(benchmark::State& state) {
  static const TriangleSoup tree = make_tree(kTreeDensity);
  raster_frame(state, tree, frame_looking_at(glm::vec3(0.0f, 0.9f, 2.3f), glm::vec3(0.0f, 0.88f, 0.0f)));
}

void BM_RasterFullScreenQuad(benchmark::State& state) {
  static const TriangleSoup quad = [] {
    TriangleSoup q;
    for (glm::vec2 p : {glm::vec2(-5, -5), glm::vec2(5, -5), glm::vec2(5, 5), glm::vec2(-5, 5)})
      q.positions.push_back(glm::vec4(p, -1.0f, 1.0f));
    q.triangles = {{0, 1, 2, 0}, {0, 2, 3, 0}};
    return q;
  }();
  raster_frame(state, quad, frame_looking_at(glm::vec3(0.0f), glm::vec3(0.0f, 0.0f, -1.0f)));
}

BENCHMARK(BM_RasterTree)->UseManualTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_RasterFullScreenQuad)->UseManualTime()->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace voxr
