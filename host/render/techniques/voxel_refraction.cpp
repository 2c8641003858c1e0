// Refraction through the scene's voxels (render/voxel_refraction.h): voxel-multi (Chang et al., PG 2011 §5,
// Snell-law marching refracting at every boundary) and voxel-two (Chang & Lai, TR 1688 §5, exact front
// surface, marched back surface). One frame: voxelize the scene on its grids (build: fine and coarse, or the
// whole scene's), march every pixel that sees a dielectric (trace).
#include <fmt/format.h>

#include "render/technique.h"
#include "render/voxel_refraction.h"

namespace voxr {

namespace {

class VoxelRefractionTechnique final : public RefractionTechnique {
 public:
  VoxelRefractionTechnique(ClRuntime& cl, Voxelizer& voxelizer) : refraction_(cl, voxelizer) {}

  std::vector<ProgramSpec> programs(const RenderOptions&) const override { return {}; }
  void prepare(const RenderOptions& options) override { refraction_.prepare(options.refraction); }
  void set_scene(const FrameContext& ctx) override {
    refraction_.set_scene(*ctx.soup, *ctx.mesh, *ctx.host_materials);
  }
  bool writes_ends() const override { return true; }

  void trace(const FrameContext& ctx, const RenderOptions& options, cl::Buffer& ends,
             cl::Buffer& paths) override {
    refraction_.build(options.refraction);
    refraction_.trace(*ctx.camera, *ctx.primary_samples, *ctx.dielectric, *ctx.materials, ctx.material_count,
                      options.refraction, ends, paths);
    ctx.stats->refraction_grid = refraction_.grid().spec;
    ctx.stats->refraction_bytes = refraction_.device_bytes();
    const DeviceVoxelGrid* coarse = refraction_.coarse_grid();
    ctx.stats->refraction_coarse_grid = coarse ? std::optional<GridSpec>(coarse->spec) : std::nullopt;
    ctx.stats->refraction_coarse_bytes = coarse ? coarse->device_bytes() : 0;
  }

  uint64_t device_bytes() const override { return refraction_.device_bytes(); }

  TechniqueDescription describe(const FrameStats& stats, const RenderOptions& options) const override {
    const RefractionOptions& r = options.refraction;
    const glm::uvec3 d = stats.refraction_grid.dims;
    const std::optional<GridSpec>& coarse = stats.refraction_coarse_grid;
    const uint64_t fine_bytes = stats.refraction_bytes - stats.refraction_coarse_bytes;
    const double mib = 1 << 20;
    TechniqueDescription out;
    std::string grids = fmt::format("grid {}x{}x{} voxel {:.4g} {:.1f} MiB", d.x, d.y, d.z,
                                    stats.refraction_grid.voxel_size, double(fine_bytes) / mib);
    if (coarse)
      grids = fmt::format("fitted {}, coarse {}x{}x{} voxel {:.4g} {:.1f} MiB", grids, coarse->dims.x,
                          coarse->dims.y, coarse->dims.z, coarse->voxel_size,
                          double(stats.refraction_coarse_bytes) / mib);
    out.suffix = fmt::format(" ({}, {} step, {} normals)", grids, step_rule_info(r.step).name,
                             normal_kind_info(r.normals).name);
    out.report["refraction_options"] = {{"res", r.resolution},
                                        {"grid", refraction_grid_info(r.grid).name},
                                        {"step", step_rule_info(r.step).name},
                                        {"normals", normal_kind_info(r.normals).name},
                                        {"angle_threshold_deg", r.angle_threshold_deg}};
    // The fine level (or the whole scene's grid) keeps the keys it had before the coarse level came.
    nlohmann::json& grid = out.report["refraction_grid"];
    grid = {{"kind", coarse ? "fitted" : "scene"},
            {"dims", {d.x, d.y, d.z}},
            {"voxel_size", stats.refraction_grid.voxel_size},
            {"device_bytes", fine_bytes}};
    if (coarse)
      grid["coarse"] = {{"dims", {coarse->dims.x, coarse->dims.y, coarse->dims.z}},
                        {"voxel_size", coarse->voxel_size},
                        {"device_bytes", stats.refraction_coarse_bytes}};
    return out;
  }

 private:
  VoxelRefraction refraction_;
};

}  // namespace

std::unique_ptr<RefractionTechnique> make_voxel_refraction(ClRuntime& cl, Voxelizer& voxelizer) {
  return std::make_unique<VoxelRefractionTechnique>(cl, voxelizer);
}

}  // namespace voxr
