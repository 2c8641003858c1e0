// voxr bench voxelize: the slice voxelizer over meshes x resolutions, medians of repeated runs after a
// warm-up, one CSV row per case (device, counts, per-stage ms, totals with and without the upload).
#include <fmt/format.h>

#include <algorithm>
#include <fstream>
#include <sstream>

#include "bench/bench_meshes.h"
#include "bench/median.h"
#include "bench/solid_table.h"
#include "bench/table1.h"
#ifdef VOXR_WITH_OPENVDB
#include "peers/openvdb_peer.h"
#endif
#include "cl/cl_runtime.h"
#include "cli/commands.h"
#include "voxelize/slice_voxelizer.h"

namespace voxr::cli {

namespace {

struct BenchArgs {
  std::vector<std::string> meshes = default_bench_meshes();
  std::vector<uint32_t> resolutions = {128, 256, 512, 1024};
  std::string mode = "conservative";
  std::string channels = "occ";
  std::string device;
  std::string out;
  int repeat = 5;
  int warmup = 1;
};

const char* const kStages[] = {"clear",  "setup", "scan",       "expand",
                               "raster", "rank",  "attributes", "finalize"};

int run_bench_voxelize(const BenchArgs& args) {
  ClRuntime cl(args.device);
  VoxelizeOptions options;
  options.mode = parse_raster_mode(args.mode);
  options.channels = ChannelSet::parse(args.channels);
  if (options.channels.has(Channel::kInside))
    fail("--channels inside comes from solid fill: use voxr bench solid");
  SliceVoxelizer voxelizer(cl);

  std::string csv = "device,driver,mesh,triangles,res,dims,mode,channels,copies,voxels,repeats";
  for (const char* s : kStages) csv += fmt::format(",{}_ms", s);
  csv += ",upload_ms,kernels_ms,readback_ms,total_ms,total_no_upload_ms\n";
  fmt::print("device: {} (driver {})\n", cl.device().label(), cl.device().driver_version);
  fmt::print("{:<14} {:>9} {:>5} {:>16} {:>9} {:>9} {:>9} {:>9} {:>9} {:>9}\n", "mesh", "tris", "res", "dims",
             "copies", "voxels", "raster", "kernels", "total", "no upload");
  for (const std::string& name : args.meshes) {
    const BenchMesh mesh = make_bench_mesh(name);
    for (uint32_t res : args.resolutions) {
      GridRequest request;
      request.resolution = res;
      const GridSpec grid = fit_grid(mesh.soup.bounds(), request);
      std::vector<VoxelizeStats> runs;
      for (int r = 0; r < args.warmup + args.repeat; ++r) {
        VoxelizeStats stats;
        voxelizer.run(mesh.soup, grid, options, &stats);
        if (r >= args.warmup) runs.push_back(stats);
      }
      auto med = [&](auto get) {
        std::vector<double> v;
        for (const VoxelizeStats& s : runs) v.push_back(get(s));
        return median(v);
      };
      const VoxelizeStats& s0 = runs.front();
      const double total = med([](const VoxelizeStats& s) { return s.total_ms(); });
      const double no_upload = med([](const VoxelizeStats& s) { return s.kernels_ms + s.readback_ms; });
      const double kernels = med([](const VoxelizeStats& s) { return s.kernels_ms; });
      const double raster = med([](const VoxelizeStats& s) {
        const auto it = s.stage_ms.find("raster");
        return it == s.stage_ms.end() ? 0.0 : it->second;
      });
      const std::string dims = fmt::format("{}x{}x{}", grid.dims.x, grid.dims.y, grid.dims.z);
      csv += fmt::format("\"{}\",\"{}\",{},{},{},{},{},\"{}\",{},{},{}", cl.device().name,
                         cl.device().driver_version, name, s0.triangles, res, dims, args.mode,
                         options.channels.to_string(), s0.copies, s0.voxels_set, runs.size());
      for (const char* stage : kStages)
        csv += fmt::format(",{:.4f}", med([&](const VoxelizeStats& s) {
                             const auto it = s.stage_ms.find(stage);
                             return it == s.stage_ms.end() ? 0.0 : it->second;
                           }));
      csv += fmt::format(",{:.4f},{:.4f},{:.4f},{:.4f},{:.4f}\n",
                         med([](const VoxelizeStats& s) { return s.upload_ms; }), kernels,
                         med([](const VoxelizeStats& s) { return s.readback_ms; }), total, no_upload);
      fmt::print("{:<14} {:>9} {:>5} {:>16} {:>9} {:>9} {:>9.2f} {:>9.2f} {:>9.2f} {:>9.2f}\n", name,
                 s0.triangles, res, dims, s0.copies, s0.voxels_set, raster, kernels, total, no_upload);
      std::fflush(stdout);
    }
  }
  if (!args.out.empty()) {
    std::ofstream out(args.out);
    out << csv;
    if (!out) fail("{}: cannot write the CSV", args.out);
    fmt::print("wrote {}\n", args.out);
  }
  return 0;
}

// The core methods plus the CPU peers this build has.
std::vector<std::string> default_table1_methods() {
  std::vector<std::string> methods = table1_methods();
#ifdef VOXR_WITH_OPENVDB
  methods.push_back("openvdb");
#endif
  return methods;
}

void print_line(const std::string& line) {
  fmt::print("{}\n", line);
  std::fflush(stdout);
}

std::string device_description(const ClRuntime& cl) {
  return fmt::format("{} ({}, driver {})", cl.device().name, cl.device().platform_name,
                     cl.device().driver_version);
}

// Writes PREFIX + each extension's text and says so.
void write_report(const std::string& prefix, const std::vector<std::pair<std::string, std::string>>& files) {
  for (const auto& [ext, text] : files) {
    std::ofstream out(prefix + ext);
    out << text;
    if (!out) fail("{}{}: cannot write", prefix, ext);
    fmt::print("wrote {}{}\n", prefix, ext);
  }
}

struct Table1Args {
  std::vector<std::string> models;  // LABEL=MESH or MESH; empty: the papers' six sizes
  std::vector<uint32_t> resolutions = {128, 256, 512};
  std::vector<std::string> methods = default_table1_methods();
  std::string device;
  std::string out = "table1";
  int repeat = 3;
  int warmup = 1;
  bool no_accuracy = false;
};

int run_bench_table1(const Table1Args& args) {
  ClRuntime cl(args.device);
  Table1Options options;
  options.models = table1_default_models();
  if (!args.models.empty()) {
    options.models.clear();
    for (const std::string& m : args.models) {
      const size_t eq = m.find('=');
      options.models.push_back(eq == std::string::npos ? Table1Model{m, m}
                                                       : Table1Model{m.substr(0, eq), m.substr(eq + 1)});
    }
  }
  options.resolutions = args.resolutions;
  options.methods = args.methods;
#ifdef VOXR_WITH_OPENVDB
  options.peers["openvdb"] = openvdb_mesh_to_volume;
#endif
  options.repeat = args.repeat;
  options.warmup = args.warmup;
  options.accuracy = !args.no_accuracy;
  options.progress = print_line;
  const std::string device = device_description(cl);
  fmt::print("device: {}\n", device);
  const std::vector<Table1Row> rows = run_table1(cl, options);
  write_report(args.out, {{".csv", table1_csv(rows, device)}, {".md", table1_markdown(rows, device)}});
  return 0;
}

struct SolidArgs {
  SolidTableOptions options;
  std::string device;
  std::string out = "solid";
};

int run_bench_solid(const SolidArgs& args) {
  ClRuntime cl(args.device);
  SolidTableOptions options = args.options;
  options.progress = print_line;
  const std::string device = device_description(cl);
  fmt::print("device: {}\n", device);
  const std::vector<SolidTableRow> rows = run_solid_table(cl, options);
  write_report(args.out,
               {{".csv", solid_table_csv(rows, device)}, {".md", solid_table_markdown(rows, device)}});
  return 0;
}

}  // namespace

Command add_bench(CLI::App& app) {
  CLI::App* sub =
      app.add_subcommand("bench", "Benchmarks (medians of repeated runs, profiled on the device)");
  sub->require_subcommand(1);
  auto args = std::make_shared<BenchArgs>();
  CLI::App* vox = sub->add_subcommand("voxelize", "Slice voxelizer over meshes x resolutions -> CSV");
  vox->add_option("--meshes", args->meshes,
                  "benchmark meshes (torus, bunny, armadillo, ...; BASExN subdivides)")
      ->delimiter(',')
      ->capture_default_str();
  vox->add_option("--res", args->resolutions, "resolutions (voxels on the longest axis)")
      ->delimiter(',')
      ->check(CLI::Range(1u, kMaxGridDim))
      ->capture_default_str();
  vox->add_option("--mode", args->mode, "conservative or center")->capture_default_str();
  vox->add_option("--channels", args->channels, "channels to produce")->capture_default_str();
  vox->add_option("--device", args->device, "OpenCL device P:D or name substring");
  vox->add_option("--out", args->out, "CSV file");
  vox->add_option("--repeat", args->repeat, "timed runs per case (median reported)")
      ->check(CLI::Range(1, 1000))
      ->capture_default_str();
  vox->add_option("--warmup", args->warmup, "untimed runs first")
      ->check(CLI::Range(0, 100))
      ->capture_default_str();
  auto table = std::make_shared<Table1Args>();
  CLI::App* t1 = sub->add_subcommand(
      "table1", "The papers' Table 1: every method x model x resolution, time and accuracy");
  t1->add_option("--models", table->models, "LABEL=MESH or MESH (default: the papers' six triangle counts)")
      ->delimiter(',');
  t1->add_option("--res", table->resolutions, "resolutions")
      ->delimiter(',')
      ->check(CLI::Range(1u, kMaxGridDim))
      ->capture_default_str();
  t1->add_option("--methods", table->methods, "methods")->delimiter(',')->capture_default_str();
  t1->add_option("--device", table->device, "OpenCL device P:D or name substring");
  t1->add_option("--out", table->out, "output prefix: PREFIX.csv and PREFIX.md")->capture_default_str();
  t1->add_option("--repeat", table->repeat, "timed runs per case")
      ->check(CLI::Range(1, 1000))
      ->capture_default_str();
  t1->add_option("--warmup", table->warmup, "untimed runs first")
      ->check(CLI::Range(0, 100))
      ->capture_default_str();
  t1->add_flag("--no-accuracy", table->no_accuracy, "skip the accuracy measures (time only)");
  auto solid = std::make_shared<SolidArgs>();
  CLI::App* so = sub->add_subcommand(
      "solid", "Solid modes x meshes (closed and with holes): time, missing/extra voxels");
  so->add_option("--meshes", solid->options.meshes, "bench meshes")->delimiter(',')->capture_default_str();
  so->add_option("--res", solid->options.resolutions, "resolutions")
      ->delimiter(',')
      ->check(CLI::Range(1u, kMaxGridDim))
      ->capture_default_str();
  so->add_option("--device", solid->device, "OpenCL device P:D or name substring");
  so->add_option("--out", solid->out, "output prefix: PREFIX.csv and PREFIX.md")->capture_default_str();
  so->add_option("--repeat", solid->options.repeat, "timed runs per case")->check(CLI::Range(1, 1000));
  return {sub, [args, vox, table, t1, solid, so] {
            if (vox->parsed()) return run_bench_voxelize(*args);
            if (t1->parsed()) return run_bench_table1(*table);
            if (so->parsed()) return run_bench_solid(*solid);
            return 2;
          }};
}

}  // namespace voxr::cli
