#include "voxelize/slice_voxelizer.h"

#include "cl/record_bins.h"
#include "cl/scan.h"
#include "voxelize/grid_params.h"
#include "voxelize/snapped_triangle.h"

namespace voxr {

namespace {

constexpr size_t kGroup = 256;

Defines base_defines(const VoxelizeOptions& options, bool sparse = false) {
  Defines d = {{"VOXR_MODE", std::to_string(int(options.mode))}, {"WG_SIZE", std::to_string(kGroup)}};
  if (sparse) d.push_back({"VOX_SPARSE", "1"});
  const Defines channels = channel_defines();
  d.insert(d.end(), channels.begin(), channels.end());
  return d;
}

// Count and normal accumulate packed, two 64-bit words per voxel (vox_scanline.h), then vox_finalize.cl
// unpacks them; colour needs the count too (its mean divides by it).
bool packed_sums(const ChannelSet& channels) {
  return channels.has(Channel::kCount) || channels.has(Channel::kNormal) || channels.has(Channel::kColor);
}

// The kernels' VOX_COLOR_PARAMS (vox_scanline.h): the mesh's colour inputs and the colour sums, or
// placeholders (every count 0: white) when the pass has no colour or the mesh none.
struct ColorArgs {
  VoxColorParams params{};
  const cl::Buffer* vertex_rgba;
  const cl::Buffer* vertex_uv;
  const cl::Buffer* triangle_look;
  const cl::Buffer* looks;
  const cl::Buffer* texels;
  const cl::Buffer* acc;
  void set_kernel_args(cl::Kernel& kernel, cl_uint& index) const {
    kernel.setArg(index++, params);
    for (const cl::Buffer* b : {vertex_rgba, vertex_uv, triangle_look, looks, texels, acc})
      kernel.setArg(index++, *b);
  }
};

ColorArgs color_args(const DeviceColors* colors, const cl::Buffer& acc, const cl::Buffer& dummy) {
  if (!colors) return {{}, &dummy, &dummy, &dummy, &dummy, &dummy, &acc};
  return {colors->tables().params,
          &colors->vertex_rgba,
          &colors->vertex_uv,
          &colors->triangle_look,
          &colors->looks,
          &colors->texels,
          &acc};
}

}  // namespace

SliceVoxelizer::SliceVoxelizer(ClRuntime& cl, VoxelizeMethod method)
    : cl_(cl), method_(method), scratch_(cl) {
  VOXR_CHECK(method == VoxelizeMethod::kHybrid || method == VoxelizeMethod::kSlice ||
             method == VoxelizeMethod::kGrid);
}

std::vector<ProgramSpec> SliceVoxelizer::programs(const VoxelizeOptions& options) const {
  return programs_of(options, false);
}

std::vector<ProgramSpec> SliceVoxelizer::sparse_programs(const VoxelizeOptions& options) const {
  return programs_of(options, true);
}

std::vector<ProgramSpec> SliceVoxelizer::programs_of(const VoxelizeOptions& options, bool sparse) const {
  const Defines base = base_defines(options, sparse);
  const bool hybrid = method_ == VoxelizeMethod::kHybrid, grid = method_ == VoxelizeMethod::kGrid;
  std::vector<ProgramSpec> specs = scan_programs();
  specs.push_back({"vox_setup.cl", with(base, "VOX_SETUP_LIST", hybrid ? "1" : "0")});
  const int passes = options.triangle_lists ? 3 : options.channels.sparse() ? 2 : 1;
  for (int pass = 0; pass < passes; ++pass) {
    const Defines p = with(base, "VOX_PASS", std::to_string(pass));
    if (hybrid) specs.push_back({"vox_direct.cl", p});
    specs.push_back({grid ? "vox_grid.cl" : "vox_raster.cl", p});
  }
  if (!grid) {
    const std::vector<ProgramSpec> expand = RecordBins::programs();
    specs.insert(specs.end(), expand.begin(), expand.end());
  }
  if (packed_sums(options.channels)) specs.push_back({"vox_finalize.cl", base});
  if (options.triangle_lists) specs.push_back({"vox_lists.cl", base});
  return specs;
}

void SliceVoxelizer::run(const DeviceMesh& mesh, const GridSpec& grid, const VoxelizeOptions& options,
                         DeviceVoxelGrid& out, VoxelizeStats& stats) {
  run(mesh, grid, options, SliceWindow{}, out, stats);
}

void SliceVoxelizer::run(const DeviceMesh& mesh, const GridSpec& grid, const VoxelizeOptions& options,
                         const SliceWindow& window, DeviceVoxelGrid& out, VoxelizeStats& stats) {
  auto progress = [&](const char* stage) {
    if (options.progress) options.progress(stage);
  };
  const bool hybrid = method_ == VoxelizeMethod::kHybrid, grid_method = method_ == VoxelizeMethod::kGrid;
  const uint32_t margin =
      options.mode == RasterMode::kConservative ? snap_margin(grid, mesh.bounds()) + window.extra_margin : 0;
  const uint64_t tris = mesh.triangle_count();
  const bool sparse = window.bricks != nullptr;
  const Defines base = base_defines(options, sparse);
  const uint32_t slices = window.slices ? window.slices : grid.dims.z;
  VOXR_CHECK_LE(uint64_t(window.first_slice) + slices, uint64_t(grid.dims.z));
  // The kernels' grid: the window's slices, snapped z relative to its first.
  auto grid_params = [&](uint32_t count, uint32_t rows, uint32_t channel_bits) {
    VoxGridParams p = make_grid_params(grid, count, margin, rows, channel_bits);
    p.dims[2] = slices;
    p.first_slice = window.first_slice;
    return p;
  };
  const uint32_t channels = options.channels.bits;
  const bool packed = packed_sums(options.channels);
  uint64_t scratch_bytes = 0;
  auto scratch = [&](const std::string& what, uint64_t bytes) {
    scratch_bytes += bytes;
    return scratch_.get(what, bytes);
  };

  // Refuse what the packed count/normal sums cannot hold before any work.
  if (packed) {
    if (tris > VOXR_MAX_ATTRIBUTE_TRIANGLES)
      fail(
          "{} triangles are more than the {} the packed count/normal sums hold exactly; drop count,normal or "
          "split the mesh",
          tris, VOXR_MAX_ATTRIBUTE_TRIANGLES);
    if (cl_.device().extensions.find("cl_khr_int64_base_atomics") == std::string::npos)
      fail("{} lacks cl_khr_int64_base_atomics, which the count and normal channels need",
           cl_.device().label());
  }

  progress("surface");
  cl::Buffer& occ = out.occupancy_for_writing(cl_);
  cl::Buffer dummy = scratch("unused channel", 4);
  const cl::Buffer& bricks = sparse ? *window.bricks : dummy;
  const ColorArgs no_color = color_args(nullptr, dummy, dummy);

  // Which triangles go through the copy records: the large ones the direct pass lists (hybrid), or all.
  // With deferred counts the list's length stays on the device (`large`) and the stages after it run over
  // a capacity: the last length with headroom, at most every triangle.
  uint64_t listed = tris;
  cl::Buffer list = dummy, large = dummy;
  if (hybrid && tris > 0) {
    list = scratch("the large-triangle list", tris * 4);
    large = scratch("the large-triangle count", 4);
    cl_.fill_zero(large, 4, "clear");
    cl::Kernel direct = cl_.kernel("vox_direct.cl", "vox_direct", with(base, "VOX_PASS", "0"));
    cl_.launch("direct", direct, tris, kGroup, grid_params(uint32_t(tris), 4, 0), mesh.positions(),
               mesh.triangles(), list, large, occ, dummy, dummy, dummy, bricks, no_color);
    uint64_t& capacity = out.capacities.listed;
    if (cl_.counts_deferred() && capacity > 0) {
      listed = std::min(capacity, tris);
      cl_.read_count_later(large, 4, "readback large-triangle count", [&capacity, listed](uint64_t count) {
        if (count <= listed) return true;
        capacity = std::max(capacity, ClRuntime::with_headroom(count));
        return false;
      });
    } else {
      cl_uint count = 0;
      cl_.download(large, &count, 4, "readback large-triangle count");
      listed = count;
      capacity = ClRuntime::with_headroom(listed);
    }
    stats.direct_triangles = tris - listed;
  }
  const VoxGridParams params = grid_params(uint32_t(listed), options.rows_per_copy, channels);

  // Setup of the listed triangles: snapped records, and copy counts and boxes for the slice path.
  cl::Buffer snapped = scratch("snapped triangles", listed * sizeof(VoxSnappedTriangle));
  cl::Buffer too_large = scratch("split check", 4);
  copies_.prepare(cl_, listed);
  if (listed > 0) {
    cl_.fill_zero(too_large, 4, "clear");
    cl::Kernel setup =
        cl_.kernel("vox_setup.cl", "vox_setup", with(base, "VOX_SETUP_LIST", hybrid ? "1" : "0"));
    cl_.launch("setup", setup, listed, kGroup, params, mesh.positions(), mesh.triangles(), list, large,
               snapped, copies_.counts(), copies_.boxes(), too_large);
    if (!grid_method) copies_.scan(cl_, options.record_budget_bytes, "scan", &out.capacities.records);
    expect_no_oversized(cl_, too_large, "split check");
  }
  const uint64_t copies = copies_.records();

  // Rasterizes the listed triangles with one pass of the kernels: batches of expanded copy records (a
  // single batch is expanded once and reused by the second pass), or for the Grid baseline one launch per
  // slab.
  auto raster_listed = [&](const char* name, int pass, const VoxGridParams& params, const cl::Buffer& ranked,
                           const cl::Buffer& acc, const cl::Buffer& material, const ColorArgs& color) {
    const Defines p = with(base, "VOX_PASS", std::to_string(pass));
    if (listed == 0) return;
    if (grid_method) {
      cl::Kernel slab_kernel = cl_.kernel("vox_grid.cl", "vox_grid", p);
      for (uint32_t k = 0; k < slices; ++k)
        cl_.launch(name, slab_kernel, listed, kGroup, params, snapped, cl_uint(k), occ, ranked, acc, material,
                   bricks, mesh.triangles(), color);
      return;
    }
    cl::Kernel raster = cl_.kernel("vox_raster.cl", "vox_raster", p);
    copies_.for_each_batch(cl_, "expand", [&](const cl::Buffer& records, uint32_t count) {
      cl_.launch(name, raster, count, kGroup, params, snapped, records, copies_.window_records(), occ, ranked,
                 acc, material, bricks, mesh.triangles(), color);
    });
  };
  raster_listed("raster", 0, params, dummy, dummy, dummy, no_color);

  if (options.channels.sparse()) {
    progress("attributes");
    // The sparse channels' entries: the set voxels, or with deferred counts a capacity (the last total with
    // headroom; the kernels drop ranks past it and stop at the true total on the device).
    cl::Buffer set_total = scratch("the set-voxel total", 8);
    build_rank_index(cl_, out, set_total);
    uint64_t set = 0;
    uint64_t& capacity = out.capacities.set;
    if (cl_.counts_deferred() && capacity > 0) {
      set = capacity;
      cl_.read_count_later(set_total, 8, "readback rank total", [&capacity, set](uint64_t total) {
        if (total <= set) return true;
        if (total > 0xffffffffull)
          fail("{} set voxels exceed the 2^32 limit of the attribute channels", total);
        capacity = std::max(capacity, std::min<uint64_t>(ClRuntime::with_headroom(total), 0xffffffffull));
        return false;
      });
    } else {
      cl_.download(set_total, &set, 8, "readback rank total");
      capacity = std::min<uint64_t>(ClRuntime::with_headroom(set), 0xffffffffull);
    }
    if (set > 0xffffffffull) fail("{} set voxels exceed the 2^32 limit of the attribute channels", set);
    out.voxels_set = set;
    cl::Buffer acc = dummy;
    if (packed) {
      acc = scratch("the count/normal accumulators", set * 16);
      cl_.fill_zero(acc, set * 16, "clear");
    }
    cl::Buffer material = dummy;
    if (options.channels.has(Channel::kMaterial)) {
      material = out.material.ensure(cl_, set * 4, "the material channel");
      cl_.fill_zero(material, set * 4, "clear");
    }
    // Colour: two 64-bit sums per voxel (vox_scanline.h), divided by the count in vox_finalize.cl.
    const bool colored = options.channels.has(Channel::kColor);
    cl::Buffer color_acc = dummy;
    if (colored) {
      color_acc = scratch("the colour sums", set * 16);
      cl_.fill_zero(color_acc, set * 16, "clear");
    }
    const ColorArgs color = colored ? color_args(mesh.colors(), color_acc, dummy) : no_color;
    const cl::Buffer& ranked = out.ranked.buffer;
    if (hybrid && tris > 0) {
      cl::Kernel direct = cl_.kernel("vox_direct.cl", "vox_direct", with(base, "VOX_PASS", "1"));
      VoxGridParams direct_params = grid_params(uint32_t(tris), 1, channels);
      direct_params.dims[3] = uint32_t(set);
      cl_.launch("attributes", direct, tris, kGroup, direct_params, mesh.positions(), mesh.triangles(), list,
                 dummy, occ, ranked, acc, material, bricks, color);
    }
    VoxGridParams attribute_params = params;
    attribute_params.dims[3] = uint32_t(set);
    raster_listed("attributes", 1, attribute_params, ranked, acc, material, color);

    if (packed) {
      const bool normals = options.channels.has(Channel::kNormal);
      cl::Buffer count =
          options.channels.has(Channel::kCount) ? out.count.ensure(cl_, set * 4, "the count channel") : dummy;
      cl::Buffer nsum = normals ? out.normal_sum.ensure(cl_, set * 12, "the normal sums") : dummy;
      cl::Buffer normal = normals ? out.normal.ensure(cl_, set * 12, "the normal channel") : dummy;
      cl::Buffer color_out = colored ? out.color.ensure(cl_, set * 4, "the color channel") : dummy;
      cl::Kernel finalize = cl_.kernel("vox_finalize.cl", "vox_finalize", base);
      cl_.launch("finalize", finalize, set, kGroup, acc, count, nsum, normal, cl_uint(set), set_total,
                 cl_uint(channels), color_acc, color_out);
    }

    if (options.triangle_lists) {
      progress("triangle lists");
      // count -> scan: the offsets of `set` lists and, at [set], the total of pairs.
      cl::Buffer counts = scratch("the list counts", (set + 1) * 4);
      cl::Kernel list_counts = cl_.kernel("vox_lists.cl", "list_counts", base);
      cl_.launch("lists", list_counts, set + 1, kGroup, out.count.buffer, set_total, cl_uint(set), counts);
      cl::Buffer& offsets = out.list_offsets.ensure(cl_, (set + 1) * 8, "the triangle list offsets");
      cl::Buffer pairs_total = scratch("the list total", 8);
      exclusive_scan(cl_, ScanKind::kUintToUlong, counts, offsets, set + 1, pairs_total, "lists");
      // The ids' entries: the pairs, or with deferred counts a capacity (a list past it is left unfilled
      // and the frame rendered again).
      auto check_pairs = [](uint64_t total) {
        if (total > 0xffffffffull)
          fail("{} (triangle, voxel) pairs exceed the 2^32-1 the triangle lists index; lower the resolution",
               total);
      };
      uint64_t pairs = 0;
      uint64_t& pair_capacity = out.capacities.pairs;
      if (cl_.counts_deferred() && pair_capacity > 0) {
        pairs = pair_capacity;
        cl_.read_count_later(
            pairs_total, 8, "readback list total", [&pair_capacity, pairs, check_pairs](uint64_t total) {
              check_pairs(total);
              if (total <= pairs) return true;
              pair_capacity =
                  std::max(pair_capacity, std::min<uint64_t>(ClRuntime::with_headroom(total), 0xffffffffull));
              return false;
            });
      } else {
        cl_.download(pairs_total, &pairs, 8, "readback list total");
        check_pairs(pairs);
        pair_capacity = std::min<uint64_t>(ClRuntime::with_headroom(pairs), 0xffffffffull);
      }
      cl::Buffer& ids = out.list_ids.ensure(cl_, std::max<uint64_t>(pairs, 1) * 4, "the triangle list ids");
      cl::Buffer cursors = scratch("the list cursors", (set + 1) * 8);
      cl_.queue().enqueueCopyBuffer(offsets, cursors, 0, 0, (set + 1) * 8);
      VoxGridParams list_params = params;
      list_params.dims[3] = uint32_t(set);
      list_params.list_capacity = uint32_t(pairs);
      if (hybrid && tris > 0) {
        cl::Kernel direct = cl_.kernel("vox_direct.cl", "vox_direct", with(base, "VOX_PASS", "2"));
        VoxGridParams direct_params = grid_params(uint32_t(tris), 1, channels);
        direct_params.dims[3] = uint32_t(set);
        direct_params.list_capacity = uint32_t(pairs);
        cl_.launch("lists", direct, tris, kGroup, direct_params, mesh.positions(), mesh.triangles(), list,
                   dummy, occ, ranked, cursors, ids, bricks, no_color);
      }
      raster_listed("lists", 2, list_params, ranked, cursors, ids, no_color);
      cl::Kernel sort = cl_.kernel("vox_lists.cl", "list_sort", base);
      cl_.launch("lists", sort, set, kGroup, offsets, ids, cl_uint(set), set_total, cl_ulong(pairs));
      out.list_capacity = pairs;
      out.has_triangle_lists = true;
    }
  }

  stats.triangles = tris;
  stats.copies = copies;
  stats.work_items = grid_method ? listed * slices : stats.direct_triangles + copies;
  stats.batches = copies_.batches();
  stats.margin = margin;
  stats.device_bytes += scratch_bytes + copies_.device_bytes();
}

}  // namespace voxr
