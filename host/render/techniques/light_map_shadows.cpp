// Light-space depth maps (render/light_space_maps.h): opaque, the classic depth shadow map (Williams 1978:
// every caster blocks), and filter, the game engines' opaque depth map x the light-space product of every
// transparent surface's transmittance. One frame: fit the light's grid to what the camera sees (on the
// device, DeviceLightFrame::fit: no host pass over triangles; kept from the frame before while the scene, the
// light's position or direction, the camera's view and the resolution stay the same), rasterize the scene's
// mesh from the light (build), look the maps up at the path ends (lookup).
#include <optional>

#include "render/light_space_maps.h"
#include "render/technique.h"
#include "util/clock.h"

namespace voxr {

namespace {

class LightMapShadows final : public ShadowTechnique {
 public:
  explicit LightMapShadows(ClRuntime& cl) : maps_(cl), device_frame_(cl) {}

  std::vector<ProgramSpec> programs(const RenderOptions&) const override {
    std::vector<ProgramSpec> specs = maps_.programs();
    for (const ProgramSpec& p : device_frame_.programs()) specs.push_back(p);
    return specs;
  }

  void set_scene(const FrameContext& ctx) override {
    scene_bounds_ = ctx.mesh->bounds();
    kept_.reset();
  }

  void build(const FrameContext& ctx, const RenderOptions& options) override {
    FrameStats& st = *ctx.stats;
    // Host work: the launches and the fit's arithmetic, less the wait for the casters' bounds.
    const auto fit_start = Clock::now();
    const double waited_before = ctx.cl->sync_ms();
    const LightFitKey key{*ctx.light, visible_bounds(scene_bounds_, *ctx.camera), options.shadow_resolution};
    if (!kept_ || !(*kept_ == key)) {
      frame_ = device_frame_.fit(*ctx.light, key.receivers, *ctx.mesh, options.shadow_resolution);
      kept_ = key;
    }
    st.light = frame_;
    st.host_ms += ms_since(fit_start) - (ctx.cl->sync_ms() - waited_before);
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
  DeviceLightFrame device_frame_;
  Bounds scene_bounds_;
  std::optional<LightFitKey> kept_;  // what frame_ was fitted for
  LightFrame frame_;
};

}  // namespace

std::unique_ptr<ShadowTechnique> make_light_map_shadows(ClRuntime& cl, Voxelizer&) {
  return std::make_unique<LightMapShadows>(cl);
}

}  // namespace voxr
