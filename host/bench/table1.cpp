#include "bench/table1.h"

#include <fmt/format.h>

#include <algorithm>
#include <map>

#include "bench/bench_meshes.h"
#include "util/error.h"
#include "util/median.h"
#include "voxelize/reference_overlap.h"
#include "voxelize/surface_accuracy.h"
#include "voxelize/voxelizer.h"

namespace voxr {

namespace {

// One timed voxelization with the named method.
VoxelGrid run_method(Voxelizer& voxelizer, const Table1Options& table, const std::string& method,
                     const TriangleSoup& soup, const GridSpec& grid, VoxelizeStats* stats) {
  if (const auto peer = table.peers.find(method); peer != table.peers.end())
    return peer->second(soup, grid, stats);
  return voxelizer.run(soup, grid, table1_voxelize_options(method), stats);
}

}  // namespace

VoxelizeOptions table1_voxelize_options(const std::string& method) {
  VoxelizeOptions options;
  if (method == "slicemap-uniform" || method == "slicemap-local") {
    options.method = VoxelizeMethod::kSlicemap;
    options.slicing = method == "slicemap-local" ? SlicemapSlicing::kLocal : SlicemapSlicing::kUniform;
    return options;
  }
  const size_t dash = method.find('-');
  options.method = parse_voxelize_method(method.substr(0, dash));
  if (dash != std::string::npos) options.mode = parse_raster_mode(method.substr(dash + 1));
  return options;
}

const std::vector<std::string>& table1_methods() {
  static const std::vector<std::string> methods = {"hybrid-conservative", "slice-conservative",
                                                   "slice-center",        "grid",
                                                   "slicemap-uniform",    "slicemap-local"};
  return methods;
}

std::vector<Table1Model> table1_default_models() {
  return {{"Torus", "torus"},    {"~43K", "armadillo"},     {"~97K", "elephant"},
          {"~655K", "sharkx64"}, {"~871K", "armadillox16"}, {"~1.09M", "bunnyx16"}};
}

std::vector<Table1Row> run_table1(ClRuntime& cl, const Table1Options& options) {
  for (const std::string& m : options.methods)
    if (std::find(table1_methods().begin(), table1_methods().end(), m) == table1_methods().end() &&
        !options.peers.count(m))
      fail(
          "unknown method '{}' (methods: hybrid-conservative, slice-conservative, slice-center, grid, "
          "slicemap-uniform, slicemap-local)",
          m);
  Voxelizer voxelizer(cl);
  for (const std::string& m : options.methods)
    if (!options.peers.count(m)) voxelizer.prepare(table1_voxelize_options(m));
  std::vector<Table1Row> rows;
  for (const Table1Model& model : options.models) {
    const BenchMesh mesh = make_bench_mesh(model.mesh);
    for (uint32_t res : options.resolutions) {
      GridRequest request;
      request.resolution = res;
      // In the soup's frame: its positions are relative to its anchor (voxel_surface_error reads it).
      const GridSpec grid = fit_grid(mesh.soup.bounds(), request, mesh.soup.anchor);
      const VoxelGrid exact = options.accuracy ? reference_overlap(mesh.soup, grid) : VoxelGrid{};
      for (const std::string& method : options.methods) {
        std::vector<double> kernels, total;
        VoxelGrid result;
        VoxelizeStats stats;
        for (int r = 0; r < options.warmup + options.repeat; ++r) {
          result = run_method(voxelizer, options, method, mesh.soup, grid, &stats);
          if (r < options.warmup) continue;
          kernels.push_back(stats.kernels_ms);
          total.push_back(stats.total_ms());
        }
        Table1Row row;
        row.model = model.label;
        row.mesh = model.mesh;
        row.method = method;
        row.triangles = mesh.soup.triangle_count();
        row.res = res;
        row.dims = fmt::format("{}x{}x{}", grid.dims.x, grid.dims.y, grid.dims.z);
        row.kernels_ms = median(kernels);
        row.kernels_min_ms = *std::min_element(kernels.begin(), kernels.end());
        row.kernels_max_ms = *std::max_element(kernels.begin(), kernels.end());
        row.grid_bytes = result.occ.size() * sizeof(result.occ[0]);
        row.total_ms = median(total);
        row.voxels = result.voxels_set;
        if (options.accuracy) {
          const SurfaceAccuracy a = measure_surface_accuracy(result, exact, mesh.soup);
          row.exact_voxels = a.exact_voxels;
          row.false_positives = a.false_positives;
          row.false_negatives = a.false_negatives;
          row.crossings = a.crossings;
          row.tunnels = a.tunnels;
        }
        if (options.surface_error) row.surface_error = options.surface_error(result, grid, mesh.soup);
        rows.push_back(row);
        if (options.progress)
          options.progress(
              fmt::format("{:<8} {:>9} {:>5} {:<20} kernels {:>10.2f} ms  total {:>10.2f} ms  FN {:>9}  "
                          "tunnels {:>8}",
                          row.model, row.triangles, row.res, row.method, row.kernels_ms, row.total_ms,
                          row.false_negatives, row.tunnels));
      }
    }
  }
  return rows;
}

std::string table1_csv(const std::vector<Table1Row>& rows, const std::string& device) {
  std::string csv =
      "device,model,mesh,triangles,res,dims,method,kernels_ms,total_ms,voxels,exact_voxels,false_positives,"
      "false_negatives,crossings,tunnels\n";
  for (const Table1Row& r : rows)
    csv += fmt::format("\"{}\",{},{},{},{},{},{},{:.4f},{:.4f},{},{},{},{},{},{}\n", device, r.model, r.mesh,
                       r.triangles, r.res, r.dims, r.method, r.kernels_ms, r.total_ms, r.voxels,
                       r.exact_voxels, r.false_positives, r.false_negatives, r.crossings, r.tunnels);
  return csv;
}

std::string table1_markdown(const std::vector<Table1Row>& rows, const std::string& device) {
  std::vector<std::string> models, methods;
  std::vector<uint32_t> resolutions;
  std::map<std::string, uint64_t> triangles;
  std::map<std::tuple<std::string, uint32_t, std::string>, const Table1Row*> cell;
  auto add_unique = [](auto& list, const auto& value) {
    if (std::find(list.begin(), list.end(), value) == list.end()) list.push_back(value);
  };
  for (const Table1Row& r : rows) {
    add_unique(models, r.model);
    add_unique(methods, r.method);
    add_unique(resolutions, r.res);
    triangles[r.model] = r.triangles;
    cell[{r.model, r.res, r.method}] = &r;
  }
  std::string md = fmt::format(
      "Kernel time in ms (median) on {}; in brackets: voxels missed against the exact triangle/box set, then "
      "tunnels (axis rays through the surface that meet no voxel).\n",
      device);
  for (uint32_t res : resolutions) {
    md += fmt::format("\n### {}³ (longest axis)\n\n| model | triangles |", res);
    std::string rule = "|---|---:|";
    for (const std::string& m : methods) {
      md += fmt::format(" {} |", m);
      rule += "---:|";
    }
    md += "\n" + rule + "\n";
    for (const std::string& model : models) {
      md += fmt::format("| {} | {} |", model, triangles[model]);
      for (const std::string& m : methods) {
        const auto it = cell.find({model, res, m});
        if (it == cell.end()) {
          md += " |";
          continue;
        }
        const Table1Row& r = *it->second;
        md += fmt::format(" {:.1f} [{}, {}] |", r.kernels_ms, r.false_negatives, r.tunnels);
      }
      md += "\n";
    }
  }
  return md;
}

}  // namespace voxr
