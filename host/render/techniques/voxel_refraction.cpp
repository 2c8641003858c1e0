// Refraction through the scene's voxels (render/voxel_refraction.h): voxel-multi (Chang et al., PG 2011 §5,
// Snell-law marching refracting at every boundary) and voxel-two (Chang & Lai, TR 1688 §5, exact front
// surface, marched back surface). One frame: voxelize the scene on its grid (build), march every pixel that
// sees a dielectric (trace).
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
  void set_scene(const FrameContext& ctx) override { refraction_.set_scene(*ctx.soup, *ctx.mesh); }
  bool writes_ends() const override { return true; }

  void trace(const FrameContext& ctx, const RenderOptions& options, cl::Buffer& ends,
             cl::Buffer& paths) override {
    refraction_.build(options.refraction);
    refraction_.trace(*ctx.camera, *ctx.primary_samples, *ctx.dielectric, *ctx.materials, ctx.material_count,
                      options.refraction, ends, paths);
    ctx.stats->refraction_grid = refraction_.grid().spec;
    ctx.stats->refraction_bytes = refraction_.grid().device_bytes();
  }

  uint64_t device_bytes() const override { return refraction_.grid().device_bytes(); }

  TechniqueDescription describe(const FrameStats& stats, const RenderOptions& options) const override {
    const RefractionOptions& r = options.refraction;
    const glm::uvec3 d = stats.refraction_grid.dims;
    TechniqueDescription out;
    out.suffix = fmt::format(" (grid {}x{}x{}, {} step, {} normals, {:.1f} MiB)", d.x, d.y, d.z,
                             step_rule_info(r.step).name, normal_kind_info(r.normals).name,
                             double(stats.refraction_bytes) / (1 << 20));
    out.report["refraction_options"] = {{"res", r.resolution},
                                        {"step", step_rule_info(r.step).name},
                                        {"normals", normal_kind_info(r.normals).name},
                                        {"angle_threshold_deg", r.angle_threshold_deg}};
    out.report["refraction_grid"] = {{"dims", {d.x, d.y, d.z}},
                                     {"voxel_size", stats.refraction_grid.voxel_size},
                                     {"device_bytes", stats.refraction_bytes}};
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
