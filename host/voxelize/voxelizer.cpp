#include "voxelize/voxelizer.h"

#include "util/clock.h"
#include "voxelize/slice_voxelizer.h"
#include "voxelize/slicemap_voxelizer.h"
#include "voxelize/solid_fill.h"

namespace voxr {

const MethodInfo& method_info(VoxelizeMethod method) {
  for (const MethodInfo& info : kMethods)
    if (info.method == method) return info;
  throw InternalError("method missing from kMethods");
}

VoxelizeMethod parse_voxelize_method(std::string_view name) {
  std::string known;
  for (const MethodInfo& info : kMethods) {
    if (name == info.name) return info.method;
    known += fmt::format("{}{}", known.empty() ? "" : ", ", info.name);
  }
  fail("unknown method '{}' (methods: {})", name, known);
}

std::unique_ptr<SurfaceVoxelizer> make_surface_voxelizer(ClRuntime& cl, VoxelizeMethod method) {
  switch (method) {
    case VoxelizeMethod::kHybrid:
    case VoxelizeMethod::kSlice:
    case VoxelizeMethod::kGrid:
      return std::make_unique<SliceVoxelizer>(cl, method);
    case VoxelizeMethod::kSlicemap:
      return std::make_unique<SlicemapVoxelizer>(cl);
  }
  throw InternalError("method missing from make_surface_voxelizer");
}

void VoxelizeOptions::validate() const {
  const MethodInfo& info = method_info(method);
  const ChannelSet surface = surface_only().channels;
  if (!info.attributes && surface.sparse())
    fail("--method {} produces the occ channel only (asked for {})", info.name, surface.to_string());
  if (!info.modes && mode != RasterMode::kConservative)
    fail("--mode does not apply to --method {} (it samples column centres)", info.name);
  if (channels.has(Channel::kInside) && !solid)
    fail("the inside channel comes from solid voxelization: add --solid xor|late|parity|flood");
  if (rows_per_copy == 0) fail("rows per copy must be at least 1");
  if (triangle_lists && (!info.attributes || !channels.has(Channel::kCount)))
    fail("triangle lists come from the count channel of --method hybrid, slice or grid (got {} with {})",
         info.name, channels.to_string());
}

VoxelizeOptions conservative_occupancy_options() {
  VoxelizeOptions options;
  options.method = VoxelizeMethod::kHybrid;
  options.mode = RasterMode::kConservative;
  return options;
}

VoxelizeOptions VoxelizeOptions::surface_only() const {
  VoxelizeOptions surface = *this;
  surface.channels.remove(Channel::kInside);
  return surface;
}

ChannelSet VoxelizeOptions::result_channels() const {
  ChannelSet set = channels;
  if (solid) set.add(Channel::kInside);
  return set;
}

Voxelizer::Voxelizer(ClRuntime& cl) : cl_(cl) {}
Voxelizer::~Voxelizer() = default;

SurfaceVoxelizer& Voxelizer::surface(VoxelizeMethod method) {
  std::unique_ptr<SurfaceVoxelizer>& slot = surfaces_[method];
  if (!slot) slot = make_surface_voxelizer(cl_, method);
  return *slot;
}

SolidFill& Voxelizer::solid() {
  if (!solid_) solid_ = std::make_unique<SolidFill>(cl_);
  return *solid_;
}

void Voxelizer::prepare(const VoxelizeOptions& options) {
  options.validate();
  cl_.build_programs(surface(options.method).programs(options.surface_only()));
  if (options.solid) cl_.build_programs(solid().programs(*options.solid));
}

void Voxelizer::run(const DeviceMesh& mesh, const GridSpec& grid, const VoxelizeOptions& options,
                    DeviceVoxelGrid& out, VoxelizeStats* stats) {
  const auto start = Clock::now();
  options.validate();
  // Waits first only when the caller asks for the run's own times (each wait is a host synchronisation).
  if (stats) cl_.finish();
  const auto before = cl_.profiler().stats();
  out.reset(grid, options.result_channels());
  VoxelizeStats local;
  surface(options.method).run(mesh, grid, options.surface_only(), out, local);
  if (options.solid) {
    if (options.progress) options.progress("solid");
    const bool conservative_surface =
        options.mode == RasterMode::kConservative && method_info(options.method).modes;
    solid().run(mesh, grid, *options.solid, conservative_surface, out, local);
  }
  // Then, unless counts are deferred and no times are asked for: the mesh may be a caller's temporary whose
  // host arrays the kernels read in place. A frame (deferred counts) keeps its meshes past its last wait.
  if (stats || !cl_.counts_deferred()) cl_.finish("voxelizing");
  local.voxels_set = out.voxels_set;
  local.inside_voxels = out.inside_voxels;
  local.triangles_split = mesh.triangles_split();
  local.device_bytes += out.device_bytes();
  const Profiler::Split split = cl_.profiler().since(before);
  local.kernels_ms = split.kernels_ms;
  local.stage_ms = split.stage_ms;
  local.readback_ms = split.readback_ms;  // the small counts read between stages
  local.wall_ms = ms_since(start);
  if (stats) *stats = local;
}

VoxelGrid Voxelizer::run(const TriangleSoup& soup, const GridSpec& grid, const VoxelizeOptions& options,
                         VoxelizeStats* stats, const Bounds* bounds) {
  const auto start = Clock::now();
  options.validate();
  if (options.progress) options.progress("upload");
  DeviceMesh mesh =
      upload_mesh(cl_, soup, grid, options.solid ? SplitCull::kColumns : SplitCull::kGrid, bounds);
  if (options.channels.has(Channel::kColor) && !soup.colors.empty())
    mesh.attach_colors(std::make_shared<const DeviceColors>(cl_, mesh.soup_for_colors(soup), "the mesh"));
  // A CPU device sets the occupancy bits straight into the result's (zero) pages.
  BitWords occ;
  if (cl_.device().host_memory) {
    grid_.spec = grid;
    cl_.check_allocation(grid_.words() * 4, "the occupancy bits");
    occ = BitWords(grid_.words());
    if (cl_.can_use_in_place(occ.data())) grid_.adopt_occupancy(cl_, occ.data(), occ.size());
  }
  // Whatever happens below, the kernels are done with the adopted pages (and the mesh's in-place arrays)
  // before they are released.
  struct Release {
    ClRuntime& cl;
    DeviceVoxelGrid& grid;
    ~Release() {
      try {
        cl.queue().finish();
      } catch (...) {
        // already failing; the queue's error was or will be reported
      }
      grid.release_adopted();
    }
  } release{cl_, grid_};
  VoxelizeStats local;
  run(mesh, grid, options, grid_, &local);
  if (options.progress) options.progress("readback");
  const auto before = cl_.profiler().stats();
  VoxelGrid result = read_back(cl_, grid_, &occ);
  local.voxels_set = result.voxels_set;
  local.upload_ms = mesh.upload_ms();
  local.readback_ms += cl_.profiler().since(before).readback_ms;
  local.wall_ms = ms_since(start);
  if (stats) *stats = local;
  return result;
}

}  // namespace voxr
