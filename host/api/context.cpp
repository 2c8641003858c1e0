// voxr::Context and the one-shot functions (include/voxr/voxr.h): an OpenCL runtime with the voxelizers kept
// between runs, each run the CLI's job (voxelize/voxelize_job.h) so the API and `voxr voxelize` agree bit for
// bit.
#include <fmt/format.h>

#include <functional>
#include <map>
#include <mutex>

#include "api/volume_impl.h"
#include "cl/cl_runtime.h"
#include "cl/device.h"
#include "core/mesh_loader.h"
#include "util/clock.h"
#include "util/error.h"

namespace voxr {

namespace {

DeviceDescription describe(const DeviceInfo& d) {
  DeviceDescription out;
  out.id = fmt::format("{}:{}", d.platform_index, d.device_index);
  out.name = d.name;
  out.platform = d.platform_name;
  out.type = d.type;
  out.driver_version = d.driver_version;
  out.compute_units = d.compute_units;
  out.global_memory = d.global_memory;
  out.max_allocation = d.max_allocation;
  return out;
}

}  // namespace

struct Context::State {
  std::unique_ptr<ClRuntime> cl;
  std::unique_ptr<Voxelizer> voxelizer;
  std::unique_ptr<SparseVoxelizer> bricks;
  std::mutex run;      // one run at a time (the one-shot functions share a Context between threads)
  TriangleSoup spare;  // the last run's soup, whose buffers the next arrays' soup fills

  // `read` makes the input (a file read, or the caller's arrays converted) and prepares it for `options`:
  // timed with the grid fit as the report's ms.load, as the CLI times its input.
  VoxelVolume voxelize(const std::function<VoxelizeInput(VoxelizeOptions&)>& read,
                       const VoxelizeSettings& settings) {
    VoxelizeOptions options = make_voxelize_options(
        {settings.method, settings.mode, settings.slicing, settings.channels, settings.solid});
    const GridLayout layout = parse_grid_layout(settings.layout, "layout");
    const uint64_t budget =
        settings.memory_budget.empty() ? 0 : parse_memory_size(settings.memory_budget, "memory_budget");
    GridChoice choice{settings.resolution, std::nullopt, std::nullopt};
    if (settings.dims) {
      const auto& d = *settings.dims;
      if (!d[0] || !d[1] || !d[2] || d[0] > kMaxGridDim || d[1] > kMaxGridDim || d[2] > kMaxGridDim)
        fail("dims {} x {} x {}: each must be 1..{}", d[0], d[1], d[2], kMaxGridDim);
      choice.dims = glm::uvec3(d[0], d[1], d[2]);
    }
    if (settings.bounds) {
      const auto& b = *settings.bounds;
      for (double v : b)
        if (!std::isfinite(v)) fail("bounds: {} is not a finite number", v);
      if (!(b[0] < b[3] && b[1] < b[4] && b[2] < b[5]))
        fail("bounds {}, {}, {}, {}, {}, {}: expected x0 < x1, y0 < y1, z0 < z1", b[0], b[1], b[2], b[3],
             b[4], b[5]);
      choice.bounds = WorldBox(glm::dvec3(b[0], b[1], b[2]), glm::dvec3(b[3], b[4], b[5]));
    }
    if (settings.resolution > kMaxGridDim)
      fail("resolution {}: at most {}", settings.resolution, kMaxGridDim);

    auto impl = std::make_shared<VoxelVolume::Impl>();
    const std::lock_guard lock(run);
    const auto load_start = Clock::now();
    VoxelizeInput input = read(options);
    const GridRequest request = choose_grid_request(input.request, choice);
    impl->grid = fit_grid(input.bounds, request, input.soup.anchor);
    const double load_ms = ms_since(load_start);
    voxelizer->prepare(options);
    impl->result = run_voxelize_job(*cl, *voxelizer, bricks, input, impl->grid, options, layout, budget,
                                    settings.bounds.has_value());
    VoxelizeReport& report = impl->report;
    const VoxelizeStats& stats = impl->result.stats;
    report.triangles = stats.triangles;
    report.voxels_set = stats.voxels_set;
    report.inside_voxels = stats.inside_voxels;
    report.device_bytes = stats.device_bytes;
    report.upload_ms = stats.upload_ms;
    report.kernels_ms = stats.kernels_ms;
    report.readback_ms = stats.readback_ms;
    report.wall_ms = stats.wall_ms;
    report.layout = impl->result.sparse ? "sparse" : "dense";
    report.warnings = std::move(input.warnings);
    report.warnings.insert(report.warnings.end(), impl->result.warnings.begin(), impl->result.warnings.end());
    spare = std::move(input.soup);
    nlohmann::json json = voxelize_report(input.source, *cl, impl->grid, options, impl->result);
    json["ms"]["load"] = load_ms;
    report.json = json.dump();
    return VoxelVolume(std::move(impl));
  }
};

Context::Context(const std::string& device) : state_(std::make_unique<State>()) {
  state_->cl = std::make_unique<ClRuntime>(device);
  state_->voxelizer = std::make_unique<Voxelizer>(*state_->cl);
}

Context::~Context() = default;
Context::Context(Context&&) noexcept = default;
Context& Context::operator=(Context&&) noexcept = default;

DeviceDescription Context::device() const {
  return describe(state_->cl->device());
}

VoxelVolume Context::voxelize(const MeshView& mesh, const VoxelizeSettings& settings) {
  return state_->voxelize(
      [&](VoxelizeOptions& options) {
        // A mesh file's scene (scene_from_mesh) without the scene: its grid request is the default one, and
        // soup_from_arrays has checked what validate_soup would.
        Bounds bounds;
        TriangleSoup soup = soup_from_arrays(mesh.positions, mesh.triangles, mesh.materials, mesh.name,
                                             &bounds, std::move(state_->spare));
        return prepare_voxelize_input(std::move(soup), mesh.name, GridRequest(), {}, options, true, &bounds);
      },
      settings);
}

VoxelVolume Context::voxelize_file(const std::string& path, const VoxelizeSettings& settings) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) fail("{}: no such file", path);
  return state_->voxelize(
      [&](VoxelizeOptions& options) { return prepare_voxelize_input(load_input(path), options); }, settings);
}

std::vector<DeviceDescription> devices() {
  std::vector<DeviceDescription> out;
  for (const DeviceInfo& d : list_devices()) out.push_back(describe(d));
  return out;
}

namespace {

// The process's Contexts, one per device selector, made on first use and kept until exit.
Context& shared_context(const std::string& device) {
  static std::mutex mutex;
  static std::map<std::string, std::unique_ptr<Context>> contexts;
  const std::lock_guard lock(mutex);
  std::unique_ptr<Context>& c = contexts[device];
  if (!c) c = std::make_unique<Context>(device);
  return *c;
}

}  // namespace

VoxelVolume voxelize(const MeshView& mesh, const VoxelizeSettings& settings) {
  return shared_context(settings.device).voxelize(mesh, settings);
}

VoxelVolume voxelize_file(const std::string& path, const VoxelizeSettings& settings) {
  return shared_context(settings.device).voxelize_file(path, settings);
}

}  // namespace voxr
