#include "voxelize/slicemap_voxelizer.h"

#include <algorithm>
#include <bit>

#include "cl/record_bins.h"
#include "voxelize/grid_params.h"
#include "voxr_layout.h"

namespace voxr {

namespace {

constexpr size_t kGroup = 256;
// Tile of column centres one raster work item covers (kernels/voxelize/slicemap_raster.cl); setup and raster
// must agree, so the host passes both.
constexpr uint32_t kTileRows = 8;
constexpr uint32_t kTileCols = 8;

Defines slicemap_defines(bool local) {
  return {{"WG_SIZE", std::to_string(kGroup)},
          {"SLICEMAP_TILE_ROWS", std::to_string(kTileRows)},
          {"SLICEMAP_TILE_COLS", std::to_string(kTileCols)},
          {"SLICEMAP_LOCAL", local ? "1" : "0"}};
}

}  // namespace

const char* slicemap_slicing_name(SlicemapSlicing slicing) {
  return slicing == SlicemapSlicing::kLocal ? "local" : "uniform";
}

SlicemapSlicing parse_slicemap_slicing(std::string_view name) {
  if (name == "uniform") return SlicemapSlicing::kUniform;
  if (name == "local") return SlicemapSlicing::kLocal;
  fail("unknown slicing '{}' (slicings: uniform, local)", name);
}

uint32_t Slicemap::bits_set(uint32_t i, uint32_t j) const {
  uint32_t n = 0;
  const uint64_t base = column(i, j) * words_per_column;
  for (uint32_t w = 0; w < words_per_column; ++w) n += std::popcount(bits[base + w]);
  return n;
}

uint64_t Slicemap::bits_set() const {
  uint64_t n = 0;
  for (uint32_t w : bits) n += std::popcount(w);
  return n;
}

std::vector<ProgramSpec> SlicemapVoxelizer::programs(const VoxelizeOptions& options) const {
  const bool local = options.slicing == SlicemapSlicing::kLocal;
  const Defines common = slicemap_defines(local);
  std::vector<ProgramSpec> specs = RecordBins::programs();
  specs.push_back({"slicemap_setup.cl", common});
  if (local) specs.push_back({"slicemap_raster.cl", with(common, "SLICEMAP_PASS", "0")});
  specs.push_back({"slicemap_raster.cl", with(common, "SLICEMAP_PASS", "1")});
  specs.push_back({"slicemap_voxels.cl", common});
  return specs;
}

void SlicemapVoxelizer::run(const DeviceMesh& mesh, const GridSpec& grid, const VoxelizeOptions& options,
                            DeviceVoxelGrid& out, VoxelizeStats& stats) {
  const bool local = options.slicing == SlicemapSlicing::kLocal;
  last_grid_ = grid;
  last_slicing_ = options.slicing;
  // zf < dims.z * S must fit the depth codes (uint) of the depth pass.
  VOXR_CHECK_LT(uint64_t(grid.dims.z) * VOXR_SUBVOXEL, uint64_t(0xffffffffu));
  const uint64_t tris = mesh.triangle_count();
  const VoxGridParams params = make_grid_params(grid, uint32_t(tris), 0);

  const uint64_t columns = uint64_t(grid.dims.x) * grid.dims.y;
  const uint32_t words_per_column = (grid.dims.z + 31) / 32;
  const uint64_t slicemap_words = columns * words_per_column;
  const Defines common = slicemap_defines(local);
  uint64_t device_bytes = 0;
  auto alloc = [&](uint64_t bytes, const std::string& what) {
    device_bytes += bytes;
    return scratch_.get(what, bytes);
  };

  cl::Buffer bits = alloc(slicemap_words * 4, "the slicemap");
  cl_.fill_zero(bits, slicemap_words * 4, "clear");
  cl::Buffer depth_range =
      local ? alloc(columns * 8, "the column depth ranges") : alloc(4, "unused depth ranges");
  if (local) cl_.fill_zero(depth_range, columns * 8, "clear");
  cl::Buffer snapped = alloc(tris * sizeof(VoxSnappedTriangle), "snapped triangles");
  cl::Buffer too_large = alloc(4, "split check");
  cl_.fill_zero(too_large, 4, "clear");
  tiles_.prepare(cl_, tris);
  cl::Kernel setup = cl_.kernel("slicemap_setup.cl", "slicemap_setup", common);
  cl_.launch("setup", setup, tris, kGroup, params, mesh.positions(), mesh.triangles(), snapped,
             tiles_.counts(), tiles_.boxes(), too_large);
  tiles_.scan(cl_, options.record_budget_bytes, "scan");
  expect_no_oversized(cl_, too_large, "split check");

  // Batches of tile records, expanded once when they fit one batch (the depth pass and the raster pass).
  auto raster_all = [&](const char* name, cl::Kernel& raster) {
    tiles_.for_each_batch(cl_, "expand", [&](const cl::Buffer& records, uint32_t count) {
      cl_.launch(name, raster, count, kGroup, params, snapped, records, cl_uint(count), depth_range, bits);
    });
  };
  if (local) {
    cl::Kernel depth =
        cl_.kernel("slicemap_raster.cl", "slicemap_raster", with(common, "SLICEMAP_PASS", "0"));
    raster_all("depth", depth);
  }
  cl::Kernel raster = cl_.kernel("slicemap_raster.cl", "slicemap_raster", with(common, "SLICEMAP_PASS", "1"));
  raster_all("raster", raster);

  cl::Buffer& occ = out.occupancy_for_writing(cl_);
  cl::Kernel voxels = cl_.kernel("slicemap_voxels.cl", "slicemap_voxels", common);
  cl_.launch("voxels", voxels, slicemap_words, kGroup, params, bits, depth_range, occ);

  stats.triangles = tris;
  stats.copies = tiles_.records();
  stats.work_items = tiles_.records();
  stats.batches = tiles_.batches();
  stats.device_bytes += device_bytes + tiles_.device_bytes();
}

Slicemap SlicemapVoxelizer::read_slicemap() {
  const GridSpec& grid = last_grid_;
  const bool local = last_slicing_ == SlicemapSlicing::kLocal;
  const uint64_t columns = uint64_t(grid.dims.x) * grid.dims.y;
  Slicemap slicemap;
  slicemap.spec = grid;
  slicemap.slicing = last_slicing_;
  slicemap.words_per_column = (grid.dims.z + 31) / 32;
  const uint64_t words = columns * slicemap.words_per_column;
  slicemap.bits.resize(words);
  cl_.download(scratch_.get("the slicemap", words * 4), slicemap.bits.data(), words * 4, "readback slicemap");
  if (local) {
    std::vector<uint32_t> codes(columns * 2);
    cl_.download(scratch_.get("the column depth ranges", columns * 8), codes.data(), columns * 8,
                 "readback depth ranges");
    const uint32_t z_end = grid.dims.z * uint32_t(VOXR_SUBVOXEL);
    slicemap.near.assign(columns, Slicemap::kEmptyNear);
    slicemap.far.assign(columns, 0);
    for (uint64_t c = 0; c < columns; ++c) {
      if (codes[2 * c + 1] == 0) continue;
      slicemap.near[c] = z_end - codes[2 * c];
      slicemap.far[c] = codes[2 * c + 1] - 1;
    }
  }
  return slicemap;
}

}  // namespace voxr
