// Where should per-voxel normals live for a consumer that marches rays? The DeviceVoxelGrid keeps them
// sparse, one float3 per set voxel in rank order, reached through the rank index (one 8-byte load and a
// popcount per read); the alternative is a dense float3 per voxel of the grid, addressed by the linear
// index. The bunny at 256 is voxelized once with count + normal; the dense array is scattered from the
// sparse one once on the device; then the same rays walk the whole grid (kernels/test/grid_view_bench.cl) and
// read the normal of every occupied voxel they meet, each way, plus a walk that reads no normal (the
// baseline). Times are the kernels' profiling events (UseManualTime); counters give the memory of each
// layout, the rays, the voxels visited and the normal reads.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <glm/glm.hpp>

#include "bench/bench_meshes.h"
#include "bench_runtime.h"
#include "cl/cl_runtime.h"
#include "core/grid_spec.h"
#include "grid/channel_table.h"
#include "grid/device_voxel_grid.h"
#include "voxelize/device_mesh.h"
#include "voxelize/voxelizer.h"

namespace voxr {
namespace {

constexpr size_t kGroup = 64;
constexpr uint32_t kResolution = 256;
constexpr uint32_t kRays = 1u << 16;

// The grid, its dense normal copy and the rays, built once for every benchmark of this file.
struct NormalLayouts {
  DeviceVoxelGrid grid;
  cl::Buffer dense;  // 3 floats per voxel
  cl::Buffer rays, shade, hits;
  Defines defines;
  double dense_build_ms = 0.0;  // zeroing and scattering the dense array, once
  uint64_t hits_total = 0;      // occupied voxels met by all rays (normal reads per walk)
  uint64_t visited_total = 0;   // voxels visited by all rays
  std::string error;            // set when the mesh is missing or the two layouts disagree
};

// `n` rays in grid units from random points on a sphere around the grid through random points of its
// middle half: most cross the surface, all leave through the far side. Fixed seed.
std::vector<glm::vec4> make_rays(glm::vec3 dims, uint32_t n) {
  std::mt19937 rng(1);
  std::uniform_real_distribution<float> u(0.0f, 1.0f), s(-1.0f, 1.0f);
  const glm::vec3 centre = dims * 0.5f;
  const float radius = glm::length(dims);
  std::vector<glm::vec4> rays;
  rays.reserve(size_t(n) * 2);
  while (rays.size() < size_t(n) * 2) {
    const glm::vec3 v(s(rng), s(rng), s(rng));
    if (glm::dot(v, v) > 1.0f || glm::dot(v, v) < 1e-4f) continue;
    const glm::vec3 origin = centre + radius * glm::normalize(v);
    const glm::vec3 target = dims * (glm::vec3(0.25f) + 0.5f * glm::vec3(u(rng), u(rng), u(rng)));
    rays.push_back(glm::vec4(origin, 0.0f));
    rays.push_back(glm::vec4(glm::normalize(target - origin), 0.0f));
  }
  return rays;
}

// Runs march kernel `name` (dense: with the dense array) over every ray; returns its profiled time.
double march(NormalLayouts& b, const std::string& name, bool dense) {
  ClRuntime& cl = bench_runtime();
  cl::Kernel kernel = cl.kernel("grid_view_bench.cl", name, b.defines);
  const double before = cl.profiler().total_ms(name);
  if (dense)
    cl.launch(name, kernel, kRays, kGroup, b.grid.view_args(cl), b.dense, b.rays, cl_uint(kRays), b.shade,
              b.hits);
  else
    cl.launch(name, kernel, kRays, kGroup, b.grid.view_args(cl), b.rays, cl_uint(kRays), b.shade, b.hits);
  cl.finish(name);
  return cl.profiler().total_ms(name) - before;
}

NormalLayouts build() {
  ClRuntime& cl = bench_runtime();
  NormalLayouts b;
  TriangleSoup soup;
  try {
    soup = make_bench_mesh("bunny").soup;
  } catch (const Error& e) {
    b.error = e.what();
    return b;
  }
  GridRequest request;
  request.resolution = kResolution;
  const GridSpec spec = fit_grid(soup.bounds(), request);
  VoxelizeOptions options;
  options.channels = ChannelSet::parse("count,normal");
  const DeviceMesh mesh = upload_mesh(cl, soup, spec, SplitCull::kGrid);
  Voxelizer(cl).run(mesh, spec, options, b.grid);
  b.defines = channel_defines();
  b.defines.push_back({"WG_SIZE", std::to_string(kGroup)});

  const uint64_t voxels = spec.voxel_count(), words = b.grid.words();
  b.dense = cl.buffer(voxels * 12, "dense normals");
  cl.fill_zero(b.dense, voxels * 12, "zero dense normals");
  cl::Kernel scatter = cl.kernel("grid_view_bench.cl", "gv_bench_scatter_normals", b.defines);
  cl.launch("gv_bench_scatter_normals", scatter, words, kGroup, b.grid.view_args(cl), cl_ulong(words),
            b.dense);
  cl.finish("scattering normals");
  b.dense_build_ms =
      cl.profiler().total_ms("zero dense normals") + cl.profiler().total_ms("gv_bench_scatter_normals");

  const std::vector<glm::vec4> rays = make_rays(glm::vec3(spec.dims), kRays);
  b.rays = cl.buffer(rays.size() * 16, "bench rays");
  cl.upload(b.rays, rays.data(), rays.size() * 16, "upload rays");
  b.shade = cl.buffer(kRays * 4, "bench shade");
  b.hits = cl.buffer(kRays * 4, "bench hits");

  // Both layouts must give the same sums, bit for bit (same normals, same order of additions).
  std::vector<float> sparse_shade(kRays), dense_shade(kRays);
  std::vector<uint32_t> hits(kRays);
  march(b, "gv_bench_march_sparse", false);
  cl.download(b.shade, sparse_shade.data(), kRays * 4, "download shade");
  cl.download(b.hits, hits.data(), kRays * 4, "download hits");
  march(b, "gv_bench_march_dense", true);
  cl.download(b.shade, dense_shade.data(), kRays * 4, "download shade");
  std::vector<float> visited(kRays);
  march(b, "gv_bench_march_occupancy", false);
  cl.download(b.shade, visited.data(), kRays * 4, "download visited");
  cl.finish("checking the layouts agree");
  for (uint32_t h : hits) b.hits_total += h;
  for (float v : visited) b.visited_total += uint64_t(v);
  if (sparse_shade != dense_shade) b.error = "sparse and dense normals give different sums";
  return b;
}

NormalLayouts& layouts() {
  static NormalLayouts b = build();
  return b;
}

enum class Layout { kSparse, kDense, kNone };

void BM_GridViewNormals(benchmark::State& state, Layout layout) {
  NormalLayouts& b = layouts();
  if (!b.error.empty()) {
    state.SkipWithError(b.error.c_str());
    return;
  }
  const char* name = layout == Layout::kSparse  ? "gv_bench_march_sparse"
                     : layout == Layout::kDense ? "gv_bench_march_dense"
                                                : "gv_bench_march_occupancy";
  for (auto _ : state) state.SetIterationTime(march(b, name, layout == Layout::kDense) * 1e-3);
  const DeviceVoxelGrid& g = b.grid;
  const double mib = 1.0 / (1 << 20);
  const uint64_t occ_bytes = g.words() * 4;
  // What each layout needs to answer "normal of voxel (i, j, k)", occupancy included.
  const uint64_t sparse_bytes = occ_bytes + g.words() * 8 + g.voxels_set * 12;
  const uint64_t dense_bytes = occ_bytes + g.spec.voxel_count() * 12;
  state.counters["layout_MiB"] = double(layout == Layout::kSparse  ? sparse_bytes
                                        : layout == Layout::kDense ? dense_bytes
                                                                   : occ_bytes) *
                                 mib;
  state.counters["sparse_MiB"] = double(sparse_bytes) * mib;
  state.counters["dense_MiB"] = double(dense_bytes) * mib;
  state.counters["dense_build_ms"] = b.dense_build_ms;
  state.counters["rays"] = double(kRays);
  state.counters["voxels_visited"] = double(b.visited_total);
  state.counters["normal_reads"] = double(b.hits_total);
  state.counters["voxels_set"] = double(g.voxels_set);
  state.counters["rays/s"] =
      benchmark::Counter(double(kRays) * double(state.iterations()), benchmark::Counter::kIsRate);
  state.SetLabel(
      fmt::format("{}x{}x{} {}", g.spec.dims.x, g.spec.dims.y, g.spec.dims.z, bench_runtime().device().name));
}

// The fastest repetition too: on a shared machine it is the least disturbed one.
double fastest(const std::vector<double>& v) {
  return *std::min_element(v.begin(), v.end());
}

BENCHMARK_CAPTURE(BM_GridViewNormals, sparse_by_rank, Layout::kSparse)
    ->UseManualTime()
    ->ComputeStatistics("min", fastest)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_GridViewNormals, dense, Layout::kDense)
    ->UseManualTime()
    ->ComputeStatistics("min", fastest)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_GridViewNormals, occupancy_only, Layout::kNone)
    ->UseManualTime()
    ->ComputeStatistics("min", fastest)
    ->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace voxr
