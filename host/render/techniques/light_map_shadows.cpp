// Light-space depth maps (render/light_space_maps.h): opaque, the classic depth shadow map (Williams 1978:
// every caster blocks), and filter, the game engines' opaque depth map x the light-space product of every
// transparent surface's transmittance. One frame: fit the light's grid to what the camera sees, rasterize the
// scene's mesh from the light (build), look the maps up at the path ends (lookup).
#include "render/light_space_maps.h"
#include "render/technique.h"
#include "util/clock.h"

namespace voxr {

namespace {

class LightMapShadows final : public ShadowTechnique {
 public:
  explicit LightMapShadows(ClRuntime& cl) : maps_(cl) {}

  std::vector<ProgramSpec> programs(const RenderOptions&) const override { return maps_.programs(); }

  void build(const FrameContext& ctx, const RenderOptions& options) override {
    FrameStats& st = *ctx.stats;
    const auto fit_start = Clock::now();
    st.light = fit_light_frame(*ctx.light, visible_bounds(ctx.soup->bounds(), *ctx.camera), *ctx.soup,
                               options.shadow_resolution);
    st.host_ms += ms_since(fit_start);
    maps_.build(*ctx.mesh, st.light, *ctx.light, *ctx.materials, ctx.material_count, options.shadows);
    st.light_triangles = ctx.mesh->triangle_count();
    st.device_bytes = maps_.device_bytes();
  }

  void lookup(const FrameContext& ctx, const RenderOptions& options, const cl::Buffer& ends,
              cl::Buffer& transmittance) override {
    maps_.lookup(ends, uint32_t(ctx.pixels), *ctx.materials, ctx.material_count, *ctx.light, options.bias,
                 options.normal_offset, transmittance);
  }

  uint64_t device_bytes() const override { return maps_.device_bytes(); }

  TechniqueDescription describe(const FrameStats& stats, const RenderOptions&) const override {
    return light_grid_description(stats);
  }

 private:
  LightSpaceMaps maps_;
};

}  // namespace

std::unique_ptr<ShadowTechnique> make_light_map_shadows(ClRuntime& cl) {
  return std::make_unique<LightMapShadows>(cl);
}

}  // namespace voxr
