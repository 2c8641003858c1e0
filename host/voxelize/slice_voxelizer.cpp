#include "voxelize/slice_voxelizer.h"

#include <bit>
#include <chrono>

#include "cl/scan.h"
#include "voxelize/triangle_splitter.h"
#include "voxr_layout.h"

namespace voxr {

static_assert(sizeof(VoxGridParams) == 80, "VoxGridParams layout changed: update the kernels");
static_assert(sizeof(VoxCopy) == 8, "VoxCopy must stay 8 bytes");
static_assert(sizeof(glm::vec4) == sizeof(cl_float4) && sizeof(glm::uvec4) == sizeof(cl_uint4));

namespace {

constexpr size_t kGroup = 256;

// Profiled milliseconds per name accumulated since `before`.
}  // namespace

DeviceMesh::DeviceMesh(ClRuntime& cl, const TriangleSoup& soup) {
  if (soup.triangle_count() > 0xffffffffull) fail("{} triangles are more than 2^32-1", soup.triangle_count());
  triangle_count_ = uint32_t(soup.triangle_count());
  const uint64_t pos_bytes = soup.positions.size() * sizeof(glm::vec4);
  const uint64_t tri_bytes = soup.triangles.size() * sizeof(glm::uvec4);
  positions_ = cl.buffer(pos_bytes, "vertex positions", CL_MEM_READ_ONLY);
  triangles_ = cl.buffer(tri_bytes, "triangle indices", CL_MEM_READ_ONLY);
  cl.upload(positions_, soup.positions.data(), pos_bytes, "upload positions");
  cl.upload(triangles_, soup.triangles.data(), tri_bytes, "upload triangles");
}

void VoxelizeStats::record_times(const Profiler::Split& split, std::chrono::steady_clock::time_point start) {
  upload_ms = split.upload_ms;
  readback_ms = split.readback_ms;
  kernels_ms = split.kernels_ms;
  stage_ms = split.stage_ms;
  wall_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

VoxelGrid upload_and_voxelize(ClRuntime& cl, const TriangleSoup& soup, const GridSpec& grid,
                              VoxelizeStats* stats,
                              const std::function<VoxelGrid(const DeviceMesh&)>& voxelize) {
  const auto start = std::chrono::steady_clock::now();
  uint64_t split = 0;
  const std::optional<TriangleSoup> pieces = split_oversized_triangles(soup, grid, &split);
  cl.finish();
  const auto before = cl.profiler().stats();
  const DeviceMesh mesh(cl, pieces ? *pieces : soup);
  cl.finish("uploading the mesh");
  const double upload_ms = cl.profiler().since(before).upload_ms;
  VoxelGrid result = voxelize(mesh);
  if (stats) {
    stats->triangles_split = split;
    stats->upload_ms = upload_ms;
    stats->wall_ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  }
  return result;
}

VoxelGrid SliceVoxelizer::run(const TriangleSoup& soup, const GridSpec& grid, const VoxelizeOptions& options,
                              VoxelizeStats* stats) {
  return upload_and_voxelize(cl_, soup, grid, stats,
                             [&](const DeviceMesh& mesh) { return run(mesh, grid, options, stats); });
}

VoxelGrid SliceVoxelizer::run(const DeviceMesh& mesh, const GridSpec& grid, const VoxelizeOptions& options,
                              VoxelizeStats* stats) {
  const auto start = std::chrono::steady_clock::now();
  auto progress = [&](const char* stage) {
    if (options.progress) options.progress(stage);
  };
  cl_.finish();
  const auto before = cl_.profiler().stats();
  VOXR_CHECK(options.rows_per_copy >= 1);

  VoxGridParams params{};
  const std::array<float, 12> m = grid.world_to_grid();
  std::copy(m.begin(), m.end(), params.world_to_grid);
  for (int a = 0; a < 3; ++a) params.dims[a] = grid.dims[a];
  params.rows_per_copy = options.rows_per_copy;
  params.triangle_count = mesh.triangle_count();

  const uint64_t voxels = grid.voxel_count();
  const uint64_t words = (voxels + 31) / 32;
  const uint64_t tris = mesh.triangle_count();
  const Defines mode = {{"VOXR_MODE", std::to_string(int(options.mode))},
                        {"WG_SIZE", std::to_string(kGroup)}};
  uint64_t device_bytes = 0;
  auto alloc = [&](uint64_t bytes, const std::string& what) {
    device_bytes += bytes;
    return scratch_.get(what, bytes);
  };

  progress("setup");
  cl::Buffer occ = alloc(words * 4, "the occupancy bits");
  cl_.fill_zero(occ, words * 4, "clear");
  cl::Buffer snapped = alloc(tris * 48, "snapped triangles");
  cl::Buffer counts = alloc(tris * 4, "copy counts");
  cl::Buffer info = alloc(tris * 8, "copy info");
  cl::Buffer offsets = alloc(tris * 8, "copy offsets");
  cl::Buffer too_large = alloc(4, "split check");
  cl::Buffer dummy = alloc(4, "unused channel");
  cl_.fill_zero(too_large, 4, "clear");
  cl::Kernel setup = cl_.kernel("vox_setup.cl", "vox_setup", mode);
  cl_.launch("setup", setup, tris, kGroup, params, mesh.positions(), mesh.triangles(), snapped, counts, info,
             too_large);
  // The Grid baseline needs no copies: every slab's launch visits every triangle.
  const bool grid_method = options.method == VoxelizeMethod::kGrid;
  const uint64_t copies =
      grid_method ? 0 : exclusive_scan(cl_, ScanKind::kUintToUlong, counts, offsets, tris, "scan");
  cl_uint oversized = 0;
  cl_.download(too_large, &oversized, 4, "readback split check");
  if (oversized)
    throw InternalError(fmt::format("{} triangles exceed {} voxels; split_oversized_triangles must run first",
                                    oversized, VOXR_MAX_TRIANGLE_EXTENT));

  const uint64_t batch = std::max<uint64_t>(1, std::min(copies, options.copy_budget_bytes / sizeof(VoxCopy)));
  const uint64_t batches = copies == 0 ? 0 : (copies + batch - 1) / batch;
  cl::Buffer records = alloc(batch * sizeof(VoxCopy), "copy records");
  cl::Kernel expand = cl_.kernel("vox_expand.cl", "vox_expand", mode);
  // Rasterizes every copy with the pass's kernel: batches of expanded records (a single batch is expanded
  // once and reused by the second pass), or for the Grid baseline one launch per slab over all triangles.
  bool expanded = false;
  auto raster_all = [&](const char* name, const Defines& pass, const cl::Buffer& ranks, const cl::Buffer& acc,
                        const cl::Buffer& material) {
    if (grid_method) {
      cl::Kernel slab_kernel = cl_.kernel("vox_grid.cl", "vox_grid", pass);
      for (uint32_t k = 0; k < grid.dims.z; ++k)
        cl_.launch(name, slab_kernel, tris, kGroup, params, snapped, cl_uint(k), occ, ranks, acc, material);
      return;
    }
    cl::Kernel raster = cl_.kernel("vox_raster.cl", "vox_raster", pass);
    for (uint64_t b = 0; b < batches; ++b) {
      const uint64_t begin = b * batch, end = std::min(copies, begin + batch);
      if (batches > 1 || !expanded)
        cl_.launch("expand", expand, tris, kGroup, cl_uint(tris), counts, offsets, info, cl_ulong(begin),
                   cl_ulong(end), records);
      expanded = true;
      cl_.launch(name, raster, end - begin, kGroup, params, snapped, records, cl_uint(end - begin), occ,
                 ranks, acc, material);
    }
  };

  progress("raster");
  Defines pass0 = mode;
  pass0.push_back({"VOX_PASS", "0"});
  raster_all("raster", pass0, dummy, dummy, dummy);

  VoxelGrid out;
  out.spec = grid;
  out.channels = options.channels;
  out.occ.resize(words);
  if (options.channels.attributes()) {
    progress("attributes");
    cl::Buffer ranks = alloc(words * 8, "ranked occupancy words");
    const uint64_t set = exclusive_scan(cl_, ScanKind::kRankedWords, occ, ranks, words, "rank");
    if (set > 0xffffffffull) fail("{} set voxels exceed the 2^32 limit of the attribute channels", set);
    out.voxels_set = set;
    // Count and normal sums accumulate packed in two 64-bit words per voxel (see vox_raster.cl).
    const bool packed = options.channels.has(Channel::kCount) || options.channels.has(Channel::kNormal);
    if (packed && tris > VOXR_MAX_ATTRIBUTE_TRIANGLES)
      fail(
          "{} triangles are more than the {} the packed count/normal sums hold exactly; drop count,normal or "
          "split the mesh",
          tris, VOXR_MAX_ATTRIBUTE_TRIANGLES);
    if (packed && cl_.device().extensions.find("cl_khr_int64_base_atomics") == std::string::npos)
      fail("{} lacks cl_khr_int64_base_atomics, which the count and normal channels need",
           cl_.device().label());
    auto zeroed = [&](bool wanted, uint64_t bytes, const char* what) {
      if (!wanted) return dummy;
      cl::Buffer b = alloc(bytes, what);
      cl_.fill_zero(b, bytes, "clear");
      return b;
    };
    cl::Buffer acc = zeroed(packed, set * 16, "the count/normal accumulators");
    cl::Buffer material = zeroed(options.channels.has(Channel::kMaterial), set * 4, "the material channel");
    const std::string channel_bits = std::to_string(options.channels.bits);
    Defines pass1 = mode;
    pass1.push_back({"VOX_PASS", "1"});
    pass1.push_back({"VOX_CHANNELS", channel_bits});
    raster_all("attributes", pass1, ranks, acc, material);

    if (packed) {
      const bool normals = options.channels.has(Channel::kNormal);
      cl::Buffer count = options.channels.has(Channel::kCount) ? alloc(set * 4, "the count channel") : dummy;
      cl::Buffer nsum = normals ? alloc(set * 12, "the normal sums") : dummy;
      cl::Buffer normal = normals ? alloc(set * 12, "the normal channel") : dummy;
      cl::Kernel finalize = cl_.kernel("vox_finalize.cl", "vox_finalize",
                                       {{"WG_SIZE", std::to_string(kGroup)}, {"VOX_CHANNELS", channel_bits}});
      cl_.launch("finalize", finalize, set, kGroup, acc, count, nsum, normal, cl_uint(set));
      if (options.channels.has(Channel::kCount)) {
        out.count.resize(set);
        cl_.download(count, out.count.data(), set * 4, "readback count");
      }
      if (normals) {
        static_assert(sizeof(glm::ivec3) == 12 && sizeof(glm::vec3) == 12);
        out.normal_sum.resize(set);
        out.normal.resize(set);
        cl_.download(nsum, out.normal_sum.data(), set * 12, "readback normal sums");
        cl_.download(normal, out.normal.data(), set * 12, "readback normals");
      }
    }
    if (options.channels.has(Channel::kMaterial)) {
      out.material.resize(set);
      cl_.download(material, out.material.data(), set * 4, "readback material");
    }
  }
  progress("readback");
  cl_.download(occ, out.occ.data(), words * 4, "readback occupancy");
  cl_.finish("voxelizing");
  if (!options.channels.attributes()) {
    uint64_t set = 0;
    for (uint32_t w : out.occ) set += std::popcount(w);
    out.voxels_set = set;
  }

  if (stats) {
    *stats = VoxelizeStats{};
    stats->triangles = tris;
    stats->copies = copies;
    stats->work_items = grid_method ? tris * grid.dims.z : copies;
    stats->batches = batches;
    stats->voxels_set = out.voxels_set;
    stats->device_bytes = device_bytes;
    stats->record_times(cl_.profiler().since(before), start);
  }
  return out;
}

}  // namespace voxr
