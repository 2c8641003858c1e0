// Layered distance maps (render/distance_map_refraction.h; Umenhoffer, Patow & Szirmay-Kalos, GPU Gems 3
// ch. 17). Per scene: the reference point. Per frame: the depth-peeled cube maps of the refractor and the
// environment layer, then a linear + secant search per ray.
#include <fmt/format.h>

#include "render/distance_map_refraction.h"
#include "render/technique.h"

namespace voxr {

namespace {

class DistanceMapTechnique final : public RefractionTechnique {
 public:
  explicit DistanceMapTechnique(ClRuntime& cl) : refraction_(cl) {}

  std::vector<ProgramSpec> programs(const RenderOptions&) const override { return refraction_.programs(); }
  void set_scene(const FrameContext& ctx) override { refraction_.set_scene(*ctx.soup, *ctx.host_materials); }
  bool writes_ends() const override { return true; }

  void trace(const FrameContext& ctx, const RenderOptions& options, cl::Buffer& ends,
             cl::Buffer& paths) override {
    refraction_.trace(*ctx.mesh, *ctx.vertex_normals, *ctx.camera, *ctx.materials, ctx.material_count,
                      options.refraction, *ctx.primary_samples, *ctx.dielectric, ends, paths);
    ctx.stats->refraction_bytes = refraction_.device_bytes();
  }

  uint64_t device_bytes() const override { return refraction_.device_bytes(); }

  TechniqueDescription describe(const FrameStats&, const RenderOptions& options) const override {
    const RefractionOptions& r = options.refraction;
    TechniqueDescription out;
    out.suffix = fmt::format(" ({} layers + environment, {}x{} texels per cube face, at most {} interfaces)",
                             r.layers, r.layer_res, r.layer_res, r.max_events);
    out.report["refraction_options"] = {
        {"layers", r.layers}, {"layer_res", r.layer_res}, {"max_events", r.max_events}};
    return out;
  }

 private:
  DistanceMapRefraction refraction_;
};

}  // namespace

std::unique_ptr<RefractionTechnique> make_distance_map_refraction(ClRuntime& cl, Voxelizer&) {
  return std::make_unique<DistanceMapTechnique>(cl);
}

}  // namespace voxr
