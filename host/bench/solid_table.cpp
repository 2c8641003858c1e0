#include "bench/solid_table.h"

#include <fmt/format.h>

#include <algorithm>

#include "bench/bench_meshes.h"
#include "core/mesh_topology.h"
#include "util/median.h"
#include "voxelize/reference_inside.h"
#include "voxelize/voxelizer.h"

namespace voxr {

namespace {

// Profiled time of the solid fill's own stages (the surface that every run also produces left out).
double fill_ms(const VoxelizeStats& stats) {
  double ms = 0.0;
  for (const auto& [name, t] : stats.stage_ms)
    if (name.rfind("solid", 0) == 0) ms += t;
  return ms;
}

}  // namespace

std::vector<SolidTableRow> run_solid_table(ClRuntime& cl, const SolidTableOptions& options) {
  std::vector<SolidTableRow> rows;
  Voxelizer voxelizer(cl);
  for (const std::string& name : options.meshes) {
    const BenchMesh mesh = make_bench_mesh(name);
    const bool closed = mesh_topology(mesh.soup).closed();
    for (uint32_t res : options.resolutions) {
      GridRequest request;
      request.resolution = res;
      const GridSpec grid = fit_grid(mesh.soup.bounds(), request);
      const std::vector<uint32_t> reference =
          closed ? reference_inside_exact(mesh.soup, grid) : reference_inside_winding(mesh.soup, grid);
      const VoxelGrid shell = voxelizer.run(mesh.soup, grid, VoxelizeOptions{});
      for (SolidMode mode : {SolidMode::kXor, SolidMode::kLate, SolidMode::kParity, SolidMode::kFlood}) {
        VoxelizeOptions solid;
        solid.solid = mode;
        voxelizer.prepare(solid);
        VoxelGrid result;
        std::vector<double> ms;
        for (int r = 0; r < options.warmup + options.repeat; ++r) {
          VoxelizeStats stats;
          result = voxelizer.run(mesh.soup, grid, solid, &stats);
          if (r >= options.warmup) ms.push_back(fill_ms(stats));
        }
        const SolidError all = compare_inside(result, reference);
        const SolidError leaks = compare_inside(result, reference, shell.occ);
        SolidTableRow row{name, solid_mode_name(mode), closed ? "exact" : "winding", closed};
        row.triangles = mesh.soup.triangle_count();
        row.res = res;
        row.kernels_ms = median(ms);
        row.inside = result.inside_voxels;
        row.reference_inside = count_bits(reference);
        row.missing = all.missing;
        row.extra = all.extra;
        row.leak_missing = leaks.missing;
        row.leak_extra = leaks.extra;
        rows.push_back(row);
        if (options.progress)
          options.progress(
              fmt::format("{:<14} {:>5} {:<7} {:>9.2f} ms  inside {:>9}  missing {:>8}  extra {:>8}  "
                          "off-surface {:>7}/{:<7}",
                          name, res, row.mode, row.kernels_ms, row.inside, row.missing, row.extra,
                          row.leak_missing, row.leak_extra));
      }
    }
  }
  return rows;
}

std::string solid_table_csv(const std::vector<SolidTableRow>& rows, const std::string& device) {
  std::string csv =
      "device,mesh,closed,triangles,res,mode,reference,kernels_ms,inside,reference_inside,missing,extra,"
      "off_surface_missing,off_surface_extra\n";
  for (const SolidTableRow& r : rows)
    csv += fmt::format("\"{}\",{},{},{},{},{},{},{:.4f},{},{},{},{},{},{}\n", device, r.mesh,
                       r.closed ? 1 : 0, r.triangles, r.res, r.mode, r.reference, r.kernels_ms, r.inside,
                       r.reference_inside, r.missing, r.extra, r.leak_missing, r.leak_extra);
  return csv;
}

std::string solid_table_markdown(const std::vector<SolidTableRow>& rows, const std::string& device) {
  std::string md = fmt::format(
      "Solid voxelization on {}: kernel ms (median) and missing/extra voxels against the reference (exact "
      "inside test for closed meshes, generalized winding number otherwise); in brackets the errors off the "
      "conservative surface shell, where a mode leaks.\n\n| mesh | closed | res | reference inside | xor | "
      "late | "
      "parity | flood |\n|---|---|---:|---:|---:|---:|---:|---:|\n",
      device);
  for (size_t i = 0; i + 3 < rows.size(); i += 4) {
    const SolidTableRow& r = rows[i];
    md += fmt::format("| {} | {} | {} | {} |", r.mesh, r.closed ? "yes" : "no", r.res, r.reference_inside);
    for (size_t m = 0; m < 4; ++m) {
      const SolidTableRow& c = rows[i + m];
      md += fmt::format(" {:.1f} ms, {}/{} [{}/{}] |", c.kernels_ms, c.missing, c.extra, c.leak_missing,
                        c.leak_extra);
    }
    md += "\n";
  }
  return md;
}

}  // namespace voxr
