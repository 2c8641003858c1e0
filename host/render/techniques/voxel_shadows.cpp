// Transparent shadow maps from a light-space voxel grid (render/transparent_shadow_map.h): voxel (Chang &
// Lai, TR 1688 §4.1, PG 2011 §4: per-voxel optical depth from the write count and material) and uniform
// (Eisemann & Decoret, I3D 2006 §5: slicemap occupancy x one absorption constant; every occupied voxel
// blocks where all casters are opaque, and where opaque and transparent ones mix, the opaque casters block
// through a depth map of their own, LightSpaceMaps::opaque_depth). One frame: fit the light's
// grid to what the camera sees, project the casters into a point light's frustum, near-clip them and split
// those too long for the grid, all on the device from the scene's one device mesh (DeviceLightFrame: no host
// pass over triangles), voxelize with the device's one voxelizer and accumulate transmittance (build); look
// it up at the path ends (lookup). The light grid and the light mesh depend only on the scene's triangles,
// the light's position or direction, the bounds the camera sees and the resolution: while none of these
// changes (a static scene, camera and light) they are kept from the frame before, and the frame re-voxelizes
// the kept light mesh; set_scene (every frame of a deforming scene) starts over.
#include <fmt/format.h>

#include <optional>

#include "render/light_space_maps.h"
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
  VoxelShadows(ClRuntime& cl, Voxelizer& voxelizer) : map_(cl, voxelizer), opaque_(cl), device_frame_(cl) {}

  std::vector<ProgramSpec> programs(const RenderOptions&) const override { return device_frame_.programs(); }
  void prepare(const RenderOptions& options) override { map_.prepare(shadow_map_options(options)); }

  void set_scene(const FrameContext& ctx) override {
    scene_bounds_ = ctx.mesh->bounds();
    uniform_ = uniform_absorption(*ctx.soup, *ctx.host_materials);  // per scene: no frame makes the pass
    kept_.reset();
    light_mesh_ = nullptr;
  }

  void build(const FrameContext& ctx, const RenderOptions& options) override {
    FrameStats& st = *ctx.stats;
    // Host work: the launches and the fit's arithmetic, less the two waits for the counts they read back.
    const auto host_start = Clock::now();
    const double waited_before = ctx.cl->sync_ms();
    const Bounds receivers = visible_bounds(scene_bounds_, *ctx.camera);
    const LightMeshKey key{{*ctx.light, receivers, options.shadow_resolution}, options.shadows};
    if (!kept_ || !(*kept_ == key)) {
      frame_ = device_frame_.fit(*ctx.light, receivers, *ctx.mesh, options.shadow_resolution);
      light_mesh_ = &device_frame_.light_mesh(*ctx.mesh);
      tau_ = options.shadows == ShadowMethod::kUniform ? uniform_.at(frame_.mean_slab_length())
                                                       : glm::vec3(0.0f);
      kept_ = key;
    }
    st.light = frame_;
    st.host_ms += ms_since(host_start) - (ctx.cl->sync_ms() - waited_before);
    st.light_triangles = light_mesh_->triangle_count();
    map_.build(*light_mesh_, frame_, *ctx.materials, ctx.material_count, tau_, uniform_.blocks(),
               shadow_map_options(options));
    // Uniform among opaque and transparent casters: a slicemap cannot tell their voxels apart, so the opaque
    // ones block through a depth map of their own on the same columns.
    opaque_depth_ = options.shadows == ShadowMethod::kUniform && uniform_.mixed()
                        ? &opaque_.opaque_depth(*ctx.mesh, frame_, *ctx.materials, ctx.material_count)
                        : nullptr;
    st.device_bytes = device_bytes();
  }

  void lookup(const FrameContext& ctx, const RenderOptions& options, const cl::Buffer& ends,
              cl::Buffer& transmittance) override {
    map_.lookup(ends, uint32_t(ctx.pixels), *ctx.materials, ctx.material_count, *ctx.light,
                shadow_map_options(options), transmittance, opaque_depth_);
  }

  uint64_t device_bytes() const override {
    return map_.device_bytes() + (opaque_depth_ ? opaque_.device_bytes() : 0);
  }

  TechniqueDescription describe(const FrameStats& stats, const RenderOptions& options) const override {
    TechniqueDescription d = light_grid_description(stats);
    if (options.shadows == ShadowMethod::kVoxel) {
      d.suffix = fmt::format(" ({} mode)", raster_mode_name(options.mode));
      d.report["mode"] = raster_mode_name(options.mode);
    } else if (uniform_.blocks()) {
      d.suffix = " (every caster opaque: occupied voxels block)";
      d.report["uniform"] = "opaque: occupied voxels block";
    } else if (uniform_.mixed()) {
      d.suffix = " (opaque and transparent casters: the opaque ones block through a depth map of their own)";
      d.report["uniform"] = "mixed: opaque casters block through their depth map";
    }
    return d;
  }

 private:
  // What the kept light grid and mesh were made from.
  struct LightMeshKey {
    LightFitKey fit;
    ShadowMethod method;
    bool operator==(const LightMeshKey&) const = default;
  };

  TransparentShadowMap map_;
  LightSpaceMaps opaque_;                     // uniform among mixed casters: the opaque casters' depth map
  const cl::Buffer* opaque_depth_ = nullptr;  // this frame's, or none
  DeviceLightFrame device_frame_;
  Bounds scene_bounds_;
  UniformAbsorption uniform_;  // the uniform method's sums over the scene's transparent triangles
  std::optional<LightMeshKey> kept_;
  LightFrame frame_;
  // device_frame_'s light mesh, or for a directional light with nothing to split the scene's own mesh
  const DeviceMesh* light_mesh_ = nullptr;
  glm::vec3 tau_{0.0f};
};

}  // namespace

std::unique_ptr<ShadowTechnique> make_voxel_shadows(ClRuntime& cl, Voxelizer& voxelizer) {
  return std::make_unique<VoxelShadows>(cl, voxelizer);
}

}  // namespace voxr
