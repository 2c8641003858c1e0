#include "voxelize/solid_voxelizer.h"

#include <algorithm>
#include <bit>
#include <optional>

#include "cl/scan.h"
#include "voxelize/triangle_splitter.h"
#include "voxr_layout.h"

namespace voxr {

namespace {

constexpr size_t kGroup = 256;
constexpr uint32_t kRowsPerItem = 4;                     // VOX_SOLID_ROWS: rows of centres per cross item
constexpr uint64_t kItemsPerLaunch = uint64_t(1) << 30;  // cross items per launch (global sizes stay small)

// Words per z layer of the row-padded bits (kernels/vox_solid_bits.h): the layer's rows, rounded up to an odd
// number of 64-byte lines so that a sweep along z visits every cache set of a CPU device.
uint64_t slice_words_of(const GridSpec& grid) {
  const uint64_t words_x = (grid.dims.x + 31) / 32;
  uint64_t words = (uint64_t(grid.dims.y) * words_x + 15) / 16 * 16;
  if (words % 32 == 0) words += 16;
  return words;
}

// Profiled kernel milliseconds since `before` (uploads and readbacks left out), stage names prefixed.
void add_kernel_times(const Profiler& profiler, const std::map<std::string, Profiler::Stat>& before,
                      SolidStats& stats, const std::string& prefix = "") {
  const Profiler::Split split = profiler.since(before);
  stats.kernels_ms += split.kernels_ms;
  for (const auto& [name, ms] : split.stage_ms) stats.stage_ms[prefix + name] += ms;
}

}  // namespace

VoxelGrid SolidVoxelizer::run(const TriangleSoup& soup, const GridSpec& grid, SolidMode mode,
                              SolidStats* stats) {
  cl_.finish();
  SolidStats local;
  const uint64_t voxels = grid.voxel_count();
  const uint64_t words = (voxels + 31) / 32;
  const uint32_t words_x = (grid.dims.x + 31) / 32;
  const uint64_t slice_words = slice_words_of(grid);
  const uint64_t padded_bytes = slice_words * grid.dims.z * 4;
  if (slice_words > 0xffffffffull)
    fail("a {}x{} grid layer is too large for the solid kernels", grid.dims.x, grid.dims.y);

  VoxelGrid out;
  out.spec = grid;
  out.channels.add(Channel::kInside);
  out.occ.assign(words, 0u);
  cl::Buffer padded = scratch_.get("the solid bits", padded_bytes);
  if (mode == SolidMode::kFlood)
    run_flood(soup, grid, out, padded, local);
  else
    run_crossings(soup, grid, mode, padded, local);

  const auto before = cl_.profiler().stats();
  const Defines defines = {{"WG_SIZE", std::to_string(kGroup)},
                           {"VOX_SOLID_INVERT", mode == SolidMode::kFlood ? "1" : "0"}};
  cl::Kernel unpack = cl_.kernel("vox_solid_unpack.cl", "vox_solid_unpack", defines);
  cl::Buffer inside = scratch_.get("the inside bits", words * 4);
  cl_.launch("solid unpack", unpack, uint64_t(grid.dims.y) * grid.dims.z, kGroup, cl_uint(grid.dims.x),
             cl_uint(grid.dims.y), cl_uint(grid.dims.z), cl_uint(words_x), cl_uint(slice_words), padded,
             inside);
  out.inside.resize(words);
  cl_.download(inside, out.inside.data(), words * 4, "readback inside");
  cl_.finish("solid voxelization");
  for (uint32_t w : out.inside) out.inside_voxels += uint64_t(std::popcount(w));
  add_kernel_times(cl_.profiler(), before, local);
  local.inside_voxels = out.inside_voxels;
  if (stats) *stats = local;
  return out;
}

void SolidVoxelizer::run_crossings(const TriangleSoup& soup, const GridSpec& grid, SolidMode mode,
                                   cl::Buffer& padded, SolidStats& stats) {
  const std::optional<TriangleSoup> pieces =
      split_oversized_triangles(soup, grid, nullptr, SplitCull::kColumns);
  const DeviceMesh mesh(cl_, pieces ? *pieces : soup);
  cl_.finish("uploading the mesh");
  const auto before = cl_.profiler().stats();

  const uint32_t nx = grid.dims.x, ny = grid.dims.y, nz = grid.dims.z;
  const uint32_t words_x = (nx + 31) / 32;
  const cl_uint slice_words = cl_uint(slice_words_of(grid));
  const uint64_t padded_bytes = uint64_t(slice_words) * nz * 4;
  const uint64_t column_bytes = uint64_t(ny) * words_x * 4;
  const uint64_t tris = mesh.triangle_count();
  const bool late = mode == SolidMode::kLate;

  VoxGridParams params{};
  const std::array<float, 12> m = grid.world_to_grid();
  std::copy(m.begin(), m.end(), params.world_to_grid);
  for (int a = 0; a < 3; ++a) params.dims[a] = grid.dims[a];
  params.rows_per_copy = kRowsPerItem;
  params.triangle_count = uint32_t(tris);

  const std::string group = std::to_string(kGroup), rows = std::to_string(kRowsPerItem);
  cl::Buffer dummy = scratch_.get("unused solid buffer", 4);
  cl::Buffer odd = late ? scratch_.get("the column parities", column_bytes) : dummy;
  cl_.fill_zero(padded, padded_bytes, "solid clear");
  if (late) cl_.fill_zero(odd, column_bytes, "solid clear");

  if (tris > 0) {
    cl::Buffer snapped = scratch_.get("solid snapped triangles", tris * 48);
    cl::Buffer counts = scratch_.get("solid item counts", tris * 4);
    cl::Buffer offsets = scratch_.get("solid item offsets", tris * 8);
    cl::Buffer too_large = scratch_.get("solid split check", 4);
    cl_.fill_zero(too_large, 4, "solid clear");
    cl::Kernel setup =
        cl_.kernel("vox_solid_setup.cl", "vox_solid_setup", {{"WG_SIZE", group}, {"VOX_SOLID_ROWS", rows}});
    cl_.launch("solid setup", setup, tris, kGroup, params, mesh.positions(), mesh.triangles(), snapped,
               counts, too_large);
    const uint64_t items = exclusive_scan(cl_, ScanKind::kUintToUlong, counts, offsets, tris, "solid scan");
    cl_uint oversized = 0;
    cl_.download(too_large, &oversized, 4, "readback solid split check");
    if (oversized)
      throw InternalError(
          fmt::format("{} triangles exceed {} voxels; split_oversized_triangles must run first", oversized,
                      VOXR_MAX_TRIANGLE_EXTENT));
    stats.crossing_items = items;
    cl::Kernel cross = cl_.kernel("vox_solid_cross.cl", "vox_solid_cross",
                                  {{"WG_SIZE", group},
                                   {"VOX_SOLID_ROWS", rows},
                                   {"VOX_SOLID_RULE", mode == SolidMode::kXor ? "1" : "0"},
                                   {"VOX_SOLID_ODD", late ? "1" : "0"}});
    for (uint64_t base = 0; base < items; base += kItemsPerLaunch)
      cl_.launch("solid cross", cross, std::min(kItemsPerLaunch, items - base), kGroup, params, snapped,
                 counts, offsets, cl_ulong(base), cl_ulong(items), cl_uint(words_x), slice_words, padded,
                 odd);
  }

  cl::Buffer resolved = late ? scratch_.get("the resolved columns", column_bytes) : dummy;
  cl::Buffer counter = scratch_.get("solid counter", 4);
  cl_.fill_zero(counter, 4, "solid clear");
  cl::Kernel prefix = cl_.kernel("vox_solid_prefix.cl", "vox_solid_prefix",
                                 {{"WG_SIZE", group}, {"VOX_SOLID_LATE", late ? "1" : "0"}});
  const uint64_t row_words = uint64_t(ny) * words_x;
  cl_.launch("solid prefix", prefix, row_words, kGroup, cl_uint(nx), cl_uint(ny), cl_uint(nz),
             cl_uint(words_x), slice_words, padded, odd, resolved, counter);

  if (late) {
    cl_uint questionable = 0;
    cl_.download(counter, &questionable, 4, "readback questionable columns");
    stats.questionable_columns = questionable;
    cl::Kernel repair = cl_.kernel("vox_solid_repair.cl", "vox_solid_repair", {{"WG_SIZE", group}});
    cl::Buffer resolved_next = scratch_.get("the resolved columns (next)", column_bytes);
    for (cl_uint changed = questionable > 0; changed;) {
      cl_.fill_zero(counter, 4, "solid clear");
      cl_.launch("solid repair", repair, row_words, kGroup, cl_uint(nx), cl_uint(ny), cl_uint(nz),
                 cl_uint(words_x), slice_words, padded, resolved, resolved_next, counter);
      cl_.download(counter, &changed, 4, "readback solid repair flag");
      if (changed) ++stats.repair_iterations;
      std::swap(resolved, resolved_next);
    }
  }
  cl_.finish("solid voxelization");
  add_kernel_times(cl_.profiler(), before, stats);
}

void SolidVoxelizer::run_flood(const TriangleSoup& soup, const GridSpec& grid, VoxelGrid& out,
                               cl::Buffer& padded, SolidStats& stats) {
  VoxelizeOptions options;
  options.mode = RasterMode::kConservative;
  VoxelizeStats surface_stats;
  const VoxelGrid surface = surface_.run(soup, grid, options, &surface_stats);
  out.occ = surface.occ;
  out.voxels_set = surface.voxels_set;
  stats.kernels_ms += surface_stats.kernels_ms;
  for (const auto& [name, ms] : surface_stats.stage_ms) stats.stage_ms["surface " + name] += ms;

  const uint32_t nx = grid.dims.x, ny = grid.dims.y, nz = grid.dims.z;
  const uint32_t words_x = (nx + 31) / 32;
  const cl_uint slice_words = cl_uint(slice_words_of(grid));
  const uint64_t words = (grid.voxel_count() + 31) / 32;
  const uint64_t padded_words = uint64_t(slice_words) * nz;
  cl::Buffer occ = scratch_.get("the surface bits", words * 4);
  cl_.upload(occ, out.occ.data(), words * 4, "upload surface");
  cl_.finish("uploading the surface");
  const auto before = cl_.profiler().stats();

  const std::string group = std::to_string(kGroup);
  cl::Buffer free_bits = scratch_.get("the free voxels", padded_words * 4);
  cl::Kernel pack = cl_.kernel("vox_solid_pack.cl", "vox_solid_pack", {{"WG_SIZE", group}});
  cl_.launch("solid pack", pack, uint64_t(ny) * nz, kGroup, cl_uint(nx), cl_uint(ny), cl_uint(nz),
             cl_uint(words_x), slice_words, occ, free_bits, padded);

  cl::Kernel sweep_x = cl_.kernel("vox_solid_flood.cl", "vox_solid_flood_x", {{"WG_SIZE", group}});
  cl::Kernel sweep_y = cl_.kernel("vox_solid_flood.cl", "vox_solid_flood_y", {{"WG_SIZE", group}});
  cl::Kernel sweep_z = cl_.kernel("vox_solid_flood.cl", "vox_solid_flood_z", {{"WG_SIZE", group}});
  cl::Buffer changed_flag = scratch_.get("solid counter", 4);
  for (cl_uint changed = 1; changed;) {
    cl_.fill_zero(changed_flag, 4, "solid clear");
    auto sweep = [&](const char* name, cl::Kernel& kernel, uint64_t lines) {
      cl_.launch(name, kernel, lines, kGroup, cl_uint(ny), cl_uint(nz), cl_uint(words_x), slice_words,
                 free_bits, padded, changed_flag);
    };
    sweep("solid flood x", sweep_x, uint64_t(ny) * nz);
    sweep("solid flood y", sweep_y, uint64_t(nz) * words_x);
    sweep("solid flood z", sweep_z, uint64_t(ny) * words_x);
    cl_.download(changed_flag, &changed, 4, "readback solid flood flag");
    ++stats.flood_iterations;
  }
  cl_.finish("solid flood fill");
  add_kernel_times(cl_.profiler(), before, stats);
}

}  // namespace voxr
