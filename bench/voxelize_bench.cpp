// Google Benchmark of the per-frame case: a mesh uploaded once, voxelized again and again into a grid that
// stays on the device (the cases of host/bench/voxelize_cases.h). Times are the device's profiling events
// (UseManualTime), so they measure the kernels, not host waits; counters break a voxelization into its
// stages. Meshes come from host/bench/bench_meshes (Debian meshes via scripts/fetch-meshes.sh and
// VOXR_MESH_DIR).
#include <benchmark/benchmark.h>

#include <map>

#include "bench/bench_meshes.h"
#include "bench/voxelize_cases.h"
#include "bench_runtime.h"
#include "cl/cl_runtime.h"
#include "cl/scan.h"
#include "core/grid_spec.h"
#include "voxelize/voxelizer.h"

namespace voxr {
namespace {

const TriangleSoup& mesh(const std::string& name) {
  static std::map<std::string, BenchMesh> cache;
  auto it = cache.find(name);
  if (it == cache.end()) it = cache.emplace(name, make_bench_mesh(name)).first;
  return it->second.soup;
}

void voxelize(benchmark::State& state, const std::string& name, const std::string& case_name) {
  ClRuntime& cl = bench_runtime();
  const TriangleSoup* soup = nullptr;
  try {
    soup = &mesh(name);
  } catch (const Error& e) {
    state.SkipWithError(e.what());
    return;
  }
  GridRequest request;
  request.resolution = uint32_t(state.range(0));
  const GridSpec grid = fit_grid(soup->bounds(), request);
  const VoxelizeOptions options = find_voxelize_case(case_name).options();
  const DeviceMesh device_mesh =
      upload_mesh(cl, *soup, grid, options.solid ? SplitCull::kColumns : SplitCull::kGrid);
  Voxelizer voxelizer(cl);
  voxelizer.prepare(options);
  DeviceVoxelGrid out;
  std::map<std::string, double> stage_sum;
  VoxelizeStats stats;
  for (auto _ : state) {
    voxelizer.run(device_mesh, grid, options, out, &stats);
    state.SetIterationTime(stats.kernels_ms * 1e-3);
    for (const auto& [stage, ms] : stats.stage_ms) stage_sum[stage] += ms;
  }
  const double n = double(state.iterations());
  for (const auto& [stage, ms] : stage_sum) state.counters[stage + "_ms"] = ms / n;
  state.counters["readback_ms"] = stats.readback_ms;
  state.counters["triangles"] = double(stats.triangles);
  state.counters["copies"] = double(stats.copies);
  build_rank_index(cl, out);  // the set voxels of occupancy-only cases too
  state.counters["voxels"] = double(out.voxels_set);
  state.counters["tri/s"] = benchmark::Counter(double(stats.triangles) * n, benchmark::Counter::kIsRate);
  state.SetLabel(device_mesh.triangle_count() ? cl.device().name : "");
}

void BM_VoxelizeOcc(benchmark::State& state, const std::string& name) {
  voxelize(state, name, "occ");
}
void BM_VoxelizeCountNormal(benchmark::State& state, const std::string& name) {
  voxelize(state, name, "count-normal");
}
void BM_VoxelizeCenter(benchmark::State& state, const std::string& name) {
  voxelize(state, name, "center");
}
void BM_VoxelizeSlice(benchmark::State& state, const std::string& name) {
  voxelize(state, name, "slice");
}
void BM_VoxelizeSolidParity(benchmark::State& state, const std::string& name) {
  voxelize(state, name, "solid-parity");
}

// The scan kernel alone: n uint counts -> ulong offsets.
void BM_Scan(benchmark::State& state) {
  ClRuntime& cl = bench_runtime();
  const uint64_t n = uint64_t(state.range(0));
  std::vector<cl_uint> host(n, 3);
  cl::Buffer in = cl.buffer(n * 4, "scan input");
  cl::Buffer out = cl.buffer(n * 8, "scan output");
  cl.upload(in, host.data(), n * 4, "upload");
  cl.finish();
  for (auto _ : state) {
    const auto before = cl.profiler().total_ms("scan");
    exclusive_scan(cl, ScanKind::kUintToUlong, in, out, n, "scan");
    cl.finish();
    state.SetIterationTime((cl.profiler().total_ms("scan") - before) * 1e-3);
  }
  state.SetBytesProcessed(int64_t(state.iterations()) * int64_t(n) * 12);
}

BENCHMARK_CAPTURE(BM_VoxelizeOcc, torus, std::string("torus"))
    ->Arg(256)
    ->Arg(512)
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_VoxelizeOcc, bunny, std::string("bunny"))
    ->Arg(256)
    ->Arg(512)
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_VoxelizeOcc, bunnyx16, std::string("bunnyx16"))
    ->Arg(512)
    ->Arg(1024)
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_VoxelizeCountNormal, bunnyx16, std::string("bunnyx16"))
    ->Arg(512)
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_VoxelizeCenter, bunnyx16, std::string("bunnyx16"))
    ->Arg(512)
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_VoxelizeSlice, bunnyx16, std::string("bunnyx16"))
    ->Arg(512)
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_VoxelizeSolidParity, bunnyx16, std::string("bunnyx16"))
    ->Arg(512)
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Scan)->Arg(1 << 20)->Arg(1 << 24)->UseManualTime()->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace voxr

BENCHMARK_MAIN();
