#include "cli/bench_voxelize.h"

#include <fmt/format.h>
#include <unistd.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "bench/bench_meshes.h"
#include "bench/report_fields.h"
#include "bench/voxelize_cases.h"
#include "cl/cl_runtime.h"
#include "cli/bench_support.h"
#include "cli/process.h"
#include "io/atomic_file.h"
#include "io/volume_writer.h"
#include "util/clock.h"
#include "util/median.h"
#include "voxelize/sparse_voxelizer.h"
#include "voxelize/voxelizer.h"

namespace voxr::cli {

namespace {

namespace fs = std::filesystem;

struct Spread {
  double median = 0.0, min = 0.0, max = 0.0;
};

Spread spread(const std::vector<double>& v) {
  if (v.empty()) return {};
  return {median(v), *std::min_element(v.begin(), v.end()), *std::max_element(v.begin(), v.end())};
}

std::string format_spread(const Spread& s) {
  return fmt::format("{:.1f} [{:.1f}-{:.1f}]", s.median, s.min, s.max);
}

// The benchmark mesh as an ASCII OFF file for the fresh processes to read; "%.9g" round-trips every float,
// so the file voxelizes exactly like the mesh in memory.
void write_off(const TriangleSoup& soup, const fs::path& path) {
  std::FILE* f = std::fopen(path.c_str(), "w");
  if (!f) fail("{}: cannot write the benchmark mesh", path.string());
  std::string text = fmt::format("OFF\n{} {} 0\n", soup.positions.size(), soup.triangles.size());
  for (const glm::vec4& p : soup.positions)
    fmt::format_to(std::back_inserter(text), "{:.9g} {:.9g} {:.9g}\n", p.x, p.y, p.z);
  for (const glm::uvec4& t : soup.triangles)
    fmt::format_to(std::back_inserter(text), "3 {} {} {}\n", t.x, t.y, t.z);
  const bool ok = std::fwrite(text.data(), 1, text.size(), f) == text.size();
  if (std::fclose(f) != 0 || !ok) fail("{}: cannot write the benchmark mesh", path.string());
}

struct FreshRun {
  uint64_t peak_rss = 0;    // the process's peak resident memory, bytes
  double process_ms = 0.0;  // measured from here: spawn to exit
  double wall_ms = 0.0;     // the report's ms.wall
  double report_process_ms = 0.0;
};

// Runs this executable as `voxr voxelize ...` and reads its report; the report's device must be `device`.
FreshRun run_fresh(const std::vector<std::string>& arguments, const fs::path& report,
                   const std::string& device) {
  const fs::path self = executable_path();
  if (self.empty()) fail("cannot find the voxr executable to start fresh processes");
  std::vector<std::string> args = {self.string(), "voxelize"};
  args.insert(args.end(), arguments.begin(), arguments.end());
  for (const char* extra : {"-q", "--report"}) args.push_back(extra);
  args.push_back(report.string());
  const auto start = Clock::now();
  FreshRun run;
  const int status = run_program(args, &run.peak_rss);
  run.process_ms = ms_since(start);
  if (status != 0) fail("the fresh process `voxr voxelize` failed (see above)");
  std::ifstream in(report);
  const nlohmann::json r = nlohmann::json::parse(in);
  if (r["device"].get<std::string>() != device)
    fail("the fresh process ran on {}, not {}", r["device"].get<std::string>(), device);
  run.wall_ms = r["ms"]["wall"].get<double>();
  run.report_process_ms = r["ms"]["process"].get<double>();
  return run;
}

}  // namespace

int run_bench_voxelize(const BenchVoxelizeArgs& args) {
  ClRuntime cl(args.device);
  Voxelizer voxelizer(cl);
  SparseVoxelizer sparse(cl);
  std::vector<const VoxelizeCase*> cases;
  for (const std::string& name : args.cases) {
    cases.push_back(&find_voxelize_case(name));
    if (cases.back()->layout == "sparse")
      sparse.prepare(cases.back()->options());
    else
      voxelizer.prepare(cases.back()->options());
  }
  if (!args.write.empty()) check_volume_output("out." + args.write, glm::uvec3(1));
  const fs::path scratch = fs::temp_directory_path() / fmt::format("voxr-bench-{}", getpid());
  fs::create_directories(scratch);
  struct Cleanup {
    fs::path path;
    ~Cleanup() {
      std::error_code ec;
      fs::remove_all(path, ec);
    }
  } cleanup{scratch};

  std::string csv =
      "device,driver,mesh,triangles,res,dims,case,voxels,direct_triangles,copies,"
      "frame_kernels_ms,frame_kernels_min_ms,frame_kernels_max_ms,frame_wall_ms,frame_wall_min_ms,"
      "frame_wall_max_ms,job_wall_ms,job_wall_min_ms,job_wall_max_ms,fresh_wall_ms,fresh_wall_min_ms,"
      "fresh_wall_max_ms,fresh_process_ms,fresh_process_min_ms,fresh_process_max_ms,triangles_per_s,"
      "voxels_per_s,repeats,fresh_runs,load_before,load_after,write,layout,device_bytes,device_bytes_per_"
      "voxel,"
      "host_bytes,host_bytes_per_voxel,fresh_peak_rss_bytes,slabs\n";
  fmt::print("device: {} ({}, driver {})\n", cl.device().name, cl.device().platform_name,
             cl.device().driver_version);
  fmt::print(
      "times in ms, median [min-max]; frame = mesh on the device, grid stays there; job = upload + voxelize "
      "+ "
      "readback in this process (sparse: the frame is the job, there is no device-only sparse frame); fresh "
      "= a "
      "new `voxr voxelize` process{}; memory: device bytes (sparse: the largest slab's) and host bytes of "
      "the "
      "result per set voxel, fresh process peak RSS\n",
      args.write.empty() ? "" : fmt::format(" writing .{}", args.write));
  fmt::print("{:<10} {:>5} {:<19} {:>10} {:>22} {:>22} {:>22} {:>22} {:>22} {:>9} {:>7} {:>7} {:>8} {:>5}\n",
             "mesh", "res", "case", "voxels", "frame kernels", "frame wall", "job wall", "fresh ms.wall",
             "fresh process", "Mtri/s", "dev B/v", "host B/v", "RSS MiB", "load");
  for (const std::string& name : args.meshes) {
    BenchMesh mesh = make_bench_mesh(name);
    // Colour cases voxelize generated colours (the fresh processes read the OFF file: white).
    if (std::any_of(cases.begin(), cases.end(),
                    [](const VoxelizeCase* c) { return c->options().channels.has(Channel::kColor); }))
      color_by_position(mesh.soup);
    const Bounds bounds = mesh.soup.bounds();
    const fs::path mesh_file = scratch / (name + ".off");
    if (args.fresh > 0) write_off(mesh.soup, mesh_file);
    for (const VoxelizeCase* c : cases) {
      const VoxelizeOptions options = c->options();
      for (uint32_t res : args.resolutions) {
        const double load_before = load_averages()[0];
        GridRequest request;
        request.resolution = res;
        const fs::path output = args.write.empty() ? fs::path() : scratch / ("out." + args.write);
        fit_request_to_format(request, output);
        const GridSpec grid = fit_grid(bounds, request);

        const bool sparse_case = c->layout == "sparse";
        std::vector<double> frame_kernels, frame_wall, job_wall;
        VoxelizeStats frame;
        uint64_t voxels = 0, device_bytes = 0, host_bytes = 0, slabs = 0;
        if (sparse_case) {
          // The sparse job in this process (upload, slabs, readback): its kernels and wall time.
          for (int r = 0; r < args.warmup + args.repeat; ++r) {
            SparseStats sparse_stats;
            const SparseVoxelGrid result =
                sparse.run(mesh.soup, grid, options, 0, &frame, &sparse_stats, &bounds);
            voxels = result.voxels_set;
            device_bytes = sparse_stats.peak_device_bytes;
            host_bytes = result.memory_bytes();
            slabs = sparse_stats.slabs;
            if (r < args.warmup) continue;
            frame_kernels.push_back(frame.kernels_ms);
            frame_wall.push_back(frame.wall_ms);
            job_wall.push_back(frame.wall_ms);
          }
        } else {
          // Per frame: one upload, the grid stays on the device.
          DeviceMesh device_mesh = upload_mesh(
              cl, mesh.soup, grid, options.solid ? SplitCull::kColumns : SplitCull::kGrid, &bounds);
          if (options.channels.has(Channel::kColor))
            device_mesh.attach_colors(
                std::make_shared<const DeviceColors>(cl, device_mesh.soup_for_colors(mesh.soup), name));
          DeviceVoxelGrid frame_grid;
          for (int r = 0; r < args.warmup + args.repeat; ++r) {
            voxelizer.run(device_mesh, grid, options, frame_grid, &frame);
            if (r < args.warmup) continue;
            frame_kernels.push_back(frame.kernels_ms);
            frame_wall.push_back(frame.wall_ms);
          }
          build_rank_index(cl, frame_grid);  // voxels_set for occupancy-only cases
          voxels = frame_grid.voxels_set;
          device_bytes = frame_grid.device_bytes();
          host_bytes =
              dense_occupancy_bytes(grid.dims) + (frame_grid.device_bytes() - frame_grid.words() * 4 -
                                                  (frame_grid.has_rank_index ? frame_grid.words() * 8 : 0));
        }

        // The whole job in this process, and in fresh processes, interleaved.
        std::vector<double> fresh_wall, fresh_process;
        uint64_t peak_rss = 0;
        std::vector<std::string> flags = {mesh_file.string(), "--res", std::to_string(res)};
        if (!args.device.empty()) {
          flags.push_back("--device");
          flags.push_back(args.device);
        }
        const std::vector<std::string> case_flags = c->cli_flags();
        flags.insert(flags.end(), case_flags.begin(), case_flags.end());
        if (!output.empty()) {
          flags.push_back("-o");
          flags.push_back(output.string());
        }
        for (int r = 0; r < std::max(args.warmup + args.repeat, args.fresh); ++r) {
          if (!sparse_case && r < args.warmup + args.repeat) {
            VoxelizeStats job;
            voxelizer.run(mesh.soup, grid, options, &job, &bounds);
            if (r >= args.warmup) job_wall.push_back(job.wall_ms);
          }
          if (r < args.fresh) {
            const FreshRun f = run_fresh(flags, scratch / "report.json", cl.device().label());
            fresh_wall.push_back(f.wall_ms);
            fresh_process.push_back(f.process_ms);
            peak_rss = std::max(peak_rss, f.peak_rss);
          }
        }
        const double load_after = load_averages()[0];
        const Spread fk = spread(frame_kernels), fw = spread(frame_wall), jw = spread(job_wall),
                     nw = spread(fresh_wall), np = spread(fresh_process);
        const double tri_per_s = fk.median > 0 ? double(frame.triangles) / (fk.median * 1e-3) : 0.0;
        const double vox_per_s = fk.median > 0 ? double(voxels) / (fk.median * 1e-3) : 0.0;
        auto per_voxel = [&](uint64_t bytes) { return voxels ? double(bytes) / double(voxels) : 0.0; };
        const std::string dims = fmt::format("{}x{}x{}", grid.dims.x, grid.dims.y, grid.dims.z);
        csv += fmt::format(
            "\"{}\",\"{}\",{},{},{},{},{},{},{},{},{:.3f},{:.3f},{:.3f},{:.3f},{:.3f},{:.3f},{:.3f},{:.3f},{:"
            ".3f},"
            "{:.3f},{:.3f},{:.3f},{:.3f},{:.3f},{:.3f},{:.0f},{:.0f},{},{},{:.2f},{:.2f},{},{},{},{:.3f},{},{"
            ":.3f},{},{}"
            "\n",
            cl.device().name, cl.device().driver_version, name, frame.triangles, res, dims, c->name, voxels,
            frame.direct_triangles, frame.copies, fk.median, fk.min, fk.max, fw.median, fw.min, fw.max,
            jw.median, jw.min, jw.max, nw.median, nw.min, nw.max, np.median, np.min, np.max, tri_per_s,
            vox_per_s, frame_kernels.size(), fresh_wall.size(), load_before, load_after, args.write,
            c->layout, device_bytes, per_voxel(device_bytes), host_bytes, per_voxel(host_bytes), peak_rss,
            slabs);
        fmt::print(
            "{:<10} {:>5} {:<19} {:>10} {:>22} {:>22} {:>22} {:>22} {:>22} {:>9.1f} {:>7.2f} {:>7.2f} {:>8} "
            "{:>5.2f}\n",
            name, res, c->name, voxels, format_spread(fk), format_spread(fw), format_spread(jw),
            args.fresh ? format_spread(nw) : "-", args.fresh ? format_spread(np) : "-", tri_per_s * 1e-6,
            per_voxel(device_bytes), per_voxel(host_bytes),
            args.fresh ? fmt::format("{:.0f}", double(peak_rss) / (1 << 20)) : "-", load_after);
        std::fflush(stdout);
      }
    }
  }
  if (!args.out.empty()) {
    write_file_atomically(args.out, csv);
    fmt::print("wrote {}\n", args.out);
  }
  return 0;
}

}  // namespace voxr::cli
