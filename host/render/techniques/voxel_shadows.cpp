// Transparent shadow maps from a light-space voxel grid (render/transparent_shadow_map.h): voxel (Chang &
// Lai, TR 1688 §4.1, PG 2011 §4: per-voxel optical depth from the write count and material) and uniform
// (Eisemann & Decoret, I3D 2006 §5: slicemap occupancy x one absorption constant). One frame: fit the light's
// grid to what the camera sees, project the casters into a point light's frustum, upload them split for the
// grid, voxelize and accumulate transmittance (build); look it up at the path ends (lookup).
#include <fmt/format.h>

#include "render/technique.h"
#include "render/transparent_shadow_map.h"
#include "util/clock.h"

namespace voxr {

namespace {

ShadowMapOptions shadow_map_options(const RenderOptions& o) {
  ShadowMapOptions s;
  s.method = o.shadows;
  s.mode = o.mode;
  s.bias = o.bias;
  s.normal_offset = o.normal_offset;
  return s;
}

class VoxelShadows final : public ShadowTechnique {
 public:
  explicit VoxelShadows(ClRuntime& cl) : map_(cl) {}

  std::vector<ProgramSpec> programs(const RenderOptions&) const override { return {}; }
  void prepare(const RenderOptions& options) override { map_.prepare(shadow_map_options(options)); }

  void build(const FrameContext& ctx, const RenderOptions& options) override {
    FrameStats& st = *ctx.stats;
    const auto host_start = Clock::now();
    const Bounds receivers = visible_bounds(ctx.soup->bounds(), *ctx.camera);
    st.light = fit_light_frame(*ctx.light, receivers, *ctx.soup, options.shadow_resolution);
    TriangleSoup projected;
    if (st.light.projective()) projected = project_to_light_grid(*ctx.soup, st.light);
    const TriangleSoup& light_soup = st.light.projective() ? projected : *ctx.soup;
    DeviceMesh light_mesh = upload_mesh(*ctx.cl, light_soup, st.light.grid, SplitCull::kGrid);
    const glm::vec3 tau =
        options.shadows == ShadowMethod::kUniform
            ? uniform_optical_depth(*ctx.soup, *ctx.host_materials, st.light.mean_slab_length())
            : glm::vec3(0.0f);
    st.host_ms += ms_since(host_start);
    st.light_triangles = light_mesh.triangle_count();
    map_.build(light_mesh, st.light, *ctx.materials, ctx.material_count, tau, shadow_map_options(options));
    st.device_bytes = map_.device_bytes();
  }

  void lookup(const FrameContext& ctx, const RenderOptions& options, const cl::Buffer& ends,
              cl::Buffer& transmittance) override {
    map_.lookup(ends, uint32_t(ctx.pixels), *ctx.materials, ctx.material_count, *ctx.light,
                shadow_map_options(options), transmittance);
  }

  uint64_t device_bytes() const override { return map_.device_bytes(); }

  TechniqueDescription describe(const FrameStats& stats, const RenderOptions& options) const override {
    TechniqueDescription d = light_grid_description(stats);
    if (options.shadows == ShadowMethod::kVoxel) {
      d.suffix = fmt::format(" ({} mode)", raster_mode_name(options.mode));
      d.report["mode"] = raster_mode_name(options.mode);
    }
    return d;
  }

 private:
  TransparentShadowMap map_;
};

}  // namespace

std::unique_ptr<ShadowTechnique> make_voxel_shadows(ClRuntime& cl) {
  return std::make_unique<VoxelShadows>(cl);
}

}  // namespace voxr
