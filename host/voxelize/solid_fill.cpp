#include "voxelize/solid_fill.h"

#include <algorithm>

#include "cl/count_bits.h"
#include "cl/scan.h"
#include "voxelize/grid_params.h"
#include "voxelize/slice_voxelizer.h"

namespace voxr {

namespace {

constexpr size_t kGroup = 256;
constexpr uint32_t kRowsPerItem = 4;                     // VOX_SOLID_ROWS: rows of centres per cross item
constexpr uint64_t kItemsPerLaunch = uint64_t(1) << 30;  // cross items per launch (global sizes stay small)

// The row-padded layout (kernels/vox_solid_bits.h): a z layer's rows rounded up to an odd number of 64-byte
// lines, so that a sweep along z visits every cache set of a CPU device.
VoxSolidLayout solid_layout(const GridSpec& grid) {
  VoxSolidLayout layout{};
  for (int a = 0; a < 3; ++a) layout.dims[a] = grid.dims[a];
  layout.words_x = (grid.dims.x + 31) / 32;
  uint64_t words = (uint64_t(grid.dims.y) * layout.words_x + 15) / 16 * 16;
  if (words % 32 == 0) words += 16;
  if (words > 0xffffffffull)
    fail("a {}x{} grid layer is too large for the solid kernels", grid.dims.x, grid.dims.y);
  layout.slice_words = uint32_t(words);
  return layout;
}

Defines group() {
  return {{"WG_SIZE", std::to_string(kGroup)}};
}

Defines cross_defines(SolidMode mode) {
  return with(with(with(group(), "VOX_SOLID_ROWS", std::to_string(kRowsPerItem)), "VOX_SOLID_RULE",
                   mode == SolidMode::kXor ? "1" : "0"),
              "VOX_SOLID_ODD", mode == SolidMode::kLate ? "1" : "0");
}

}  // namespace

SolidFill::SolidFill(ClRuntime& cl) : cl_(cl), scratch_(cl) {}
SolidFill::~SolidFill() = default;

std::vector<ProgramSpec> SolidFill::programs(SolidMode mode) const {
  std::vector<ProgramSpec> specs = scan_programs();
  const std::vector<ProgramSpec> count = count_bits_programs();
  specs.insert(specs.end(), count.begin(), count.end());
  specs.push_back(
      {"vox_solid_unpack.cl", with(group(), "VOX_SOLID_INVERT", mode == SolidMode::kFlood ? "1" : "0")});
  if (mode == SolidMode::kFlood) {
    specs.push_back({"vox_solid_pack.cl", group()});
    specs.push_back({"vox_solid_flood.cl", group()});
    const std::vector<ProgramSpec> surface =
        SliceVoxelizer(cl_, VoxelizeMethod::kHybrid).programs(conservative_occupancy_options());
    specs.insert(specs.end(), surface.begin(), surface.end());
    return specs;
  }
  specs.push_back({"vox_solid_setup.cl", with(group(), "VOX_SOLID_ROWS", std::to_string(kRowsPerItem))});
  specs.push_back({"vox_solid_cross.cl", cross_defines(mode)});
  specs.push_back(
      {"vox_solid_prefix.cl", with(group(), "VOX_SOLID_LATE", mode == SolidMode::kLate ? "1" : "0")});
  if (mode == SolidMode::kLate) specs.push_back({"vox_solid_repair.cl", group()});
  return specs;
}

void SolidFill::run(const DeviceMesh& mesh, const GridSpec& grid, SolidMode mode,
                    bool surface_is_conservative, DeviceVoxelGrid& out, VoxelizeStats& stats) {
  const VoxSolidLayout layout = solid_layout(grid);
  const uint64_t padded_bytes = uint64_t(layout.slice_words) * grid.dims.z * 4;
  cl::Buffer padded = scratch_.get("the solid bits", padded_bytes);
  stats.device_bytes += padded_bytes;
  if (mode == SolidMode::kFlood) {
    if (surface_is_conservative) {
      run_flood(mesh, grid, out.occ.buffer, padded, stats);
    } else {
      if (!surface_) surface_ = std::make_unique<SliceVoxelizer>(cl_, VoxelizeMethod::kHybrid);
      surface_grid_.reset(grid, ChannelSet{});
      VoxelizeStats surface_stats;
      surface_->run(mesh, grid, conservative_occupancy_options(), surface_grid_, surface_stats);
      run_flood(mesh, grid, surface_grid_.occ.buffer, padded, stats);
    }
  } else {
    run_crossings(mesh, grid, mode, padded, stats);
  }

  const uint64_t words = out.words();
  cl::Kernel unpack = cl_.kernel("vox_solid_unpack.cl", "vox_solid_unpack",
                                 with(group(), "VOX_SOLID_INVERT", mode == SolidMode::kFlood ? "1" : "0"));
  cl::Buffer& inside = out.inside.ensure(cl_, words * 4, "the inside bits");
  cl_.launch("solid unpack", unpack, uint64_t(grid.dims.y) * grid.dims.z, kGroup, layout, padded, inside);
  out.inside_voxels = count_bits(cl_, inside, words, "solid count");
  stats.inside_voxels = out.inside_voxels;
}

void SolidFill::run_crossings(const DeviceMesh& mesh, const GridSpec& grid, SolidMode mode,
                              cl::Buffer& padded, VoxelizeStats& stats) {
  const VoxSolidLayout layout = solid_layout(grid);
  const uint32_t ny = grid.dims.y, nz = grid.dims.z;
  const uint64_t padded_bytes = uint64_t(layout.slice_words) * nz * 4;
  const uint64_t column_bytes = uint64_t(ny) * layout.words_x * 4;
  const uint64_t tris = mesh.triangle_count();
  const bool late = mode == SolidMode::kLate;
  const VoxGridParams params = make_grid_params(grid, uint32_t(tris), 0, kRowsPerItem);

  cl::Buffer dummy = scratch_.get("unused solid buffer", 4);
  cl::Buffer odd = late ? scratch_.get("the column parities", column_bytes) : dummy;
  cl_.fill_zero(padded, padded_bytes, "solid clear");
  if (late) cl_.fill_zero(odd, column_bytes, "solid clear");

  if (tris > 0) {
    cl::Buffer snapped = scratch_.get("solid snapped triangles", tris * sizeof(VoxSnappedTriangle));
    cl::Buffer counts = scratch_.get("solid item counts", tris * 4);
    cl::Buffer offsets = scratch_.get("solid item offsets", tris * 8);
    cl::Buffer too_large = scratch_.get("solid split check", 4);
    cl_.fill_zero(too_large, 4, "solid clear");
    cl::Kernel setup = cl_.kernel("vox_solid_setup.cl", "vox_solid_setup",
                                  with(group(), "VOX_SOLID_ROWS", std::to_string(kRowsPerItem)));
    cl_.launch("solid setup", setup, tris, kGroup, params, mesh.positions(), mesh.triangles(), snapped,
               counts, too_large);
    const uint64_t items = exclusive_scan(cl_, ScanKind::kUintToUlong, counts, offsets, tris, "solid scan");
    expect_no_oversized(cl_, too_large, "solid split check");
    stats.work_items += items;
    cl::Kernel cross = cl_.kernel("vox_solid_cross.cl", "vox_solid_cross", cross_defines(mode));
    for (uint64_t base = 0; base < items; base += kItemsPerLaunch)
      cl_.launch("solid cross", cross, std::min(kItemsPerLaunch, items - base), kGroup, params, snapped,
                 counts, offsets, cl_ulong(base), cl_ulong(items), layout, padded, odd);
  }

  cl::Buffer resolved = late ? scratch_.get("the resolved columns", column_bytes) : dummy;
  cl::Buffer counter = scratch_.get("solid counter", 4);
  cl_.fill_zero(counter, 4, "solid clear");
  cl::Kernel prefix = cl_.kernel("vox_solid_prefix.cl", "vox_solid_prefix",
                                 with(group(), "VOX_SOLID_LATE", late ? "1" : "0"));
  const uint64_t row_words = uint64_t(ny) * layout.words_x;
  cl_.launch("solid prefix", prefix, row_words, kGroup, layout, padded, odd, resolved, counter);

  if (late) {
    cl_uint questionable = 0;
    cl_.download(counter, &questionable, 4, "readback questionable columns");
    stats.questionable_columns = questionable;
    cl::Kernel repair = cl_.kernel("vox_solid_repair.cl", "vox_solid_repair", group());
    cl::Buffer resolved_next = scratch_.get("the resolved columns (next)", column_bytes);
    for (cl_uint changed = questionable > 0; changed;) {
      cl_.fill_zero(counter, 4, "solid clear");
      cl_.launch("solid repair", repair, row_words, kGroup, layout, padded, resolved, resolved_next, counter);
      cl_.download(counter, &changed, 4, "readback solid repair flag");
      if (changed) ++stats.repair_iterations;
      std::swap(resolved, resolved_next);
    }
  }
}

void SolidFill::run_flood(const DeviceMesh&, const GridSpec& grid, const cl::Buffer& surface,
                          cl::Buffer& padded, VoxelizeStats& stats) {
  const VoxSolidLayout layout = solid_layout(grid);
  const uint32_t ny = grid.dims.y, nz = grid.dims.z;
  const uint64_t padded_words = uint64_t(layout.slice_words) * nz;
  cl::Buffer free_bits = scratch_.get("the free voxels", padded_words * 4);
  cl::Kernel pack = cl_.kernel("vox_solid_pack.cl", "vox_solid_pack", group());
  cl_.launch("solid pack", pack, uint64_t(ny) * nz, kGroup, layout, surface, free_bits, padded);

  cl::Kernel sweep_x = cl_.kernel("vox_solid_flood.cl", "vox_solid_flood_x", group());
  cl::Kernel sweep_y = cl_.kernel("vox_solid_flood.cl", "vox_solid_flood_y", group());
  cl::Kernel sweep_z = cl_.kernel("vox_solid_flood.cl", "vox_solid_flood_z", group());
  cl::Buffer changed_flag = scratch_.get("solid counter", 4);
  for (cl_uint changed = 1; changed;) {
    cl_.fill_zero(changed_flag, 4, "solid clear");
    auto sweep = [&](const char* name, cl::Kernel& kernel, uint64_t lines) {
      cl_.launch(name, kernel, lines, kGroup, layout, free_bits, padded, changed_flag);
    };
    sweep("solid flood x", sweep_x, uint64_t(ny) * nz);
    sweep("solid flood y", sweep_y, uint64_t(nz) * layout.words_x);
    sweep("solid flood z", sweep_z, uint64_t(ny) * layout.words_x);
    cl_.download(changed_flag, &changed, 4, "readback solid flood flag");
    ++stats.flood_iterations;
  }
}

}  // namespace voxr
