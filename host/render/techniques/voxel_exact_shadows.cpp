// `--shadows voxel-exact` (beyond the papers): the straight shadow ray's exact transmittance through the
// frame's per-voxel triangle lists (render/triangle_grid.h), computed on the device as
// ReferenceScene::transmittance computes it (every crossing once, sheets multiplied, sigma_a x length inside
// dielectrics, an opaque crossing blocks, the receiver's depth inside glass from the crossings' winding over
// the whole ray, media_stack.h) —
// kernels/render/shadow/shadow_exact.cl. No light-space map: build makes sure the frame's TriangleGrid exists
// (resolution --shadow-res; the one voxel-exact refraction uses when its --res is the same, shared through
// FrameContext::triangle_grids), lookup marches every sample's ray through it. Nothing is kept from frame
// to frame: the grid is rebuilt every frame, deforming or not.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "cl/defines.h"
#include "grid/channel_table.h"
#include "render/technique.h"
#include "render/triangle_grid.h"
#include "util/error.h"
#include "voxelize/voxelizer.h"

namespace voxr {

namespace {

constexpr size_t kGroup = 64;  // shadow_exact.cl SHADOW_GROUP

class VoxelExactShadows final : public ShadowTechnique {
 public:
  VoxelExactShadows(ClRuntime& cl, Voxelizer& voxelizer) : cl_(cl), voxelizer_(voxelizer) {}

  std::vector<ProgramSpec> programs(const RenderOptions&) const override {
    std::vector<ProgramSpec> specs = TriangleGrid::programs();
    specs.push_back({"shadow_exact.cl", defines()});
    return specs;
  }
  void prepare(const RenderOptions&) override { voxelizer_.prepare(TriangleGrid::voxelize_options()); }

  void set_scene(const FrameContext& ctx) override {
    // The reference's tolerances (shadow_tolerances.h) are fractions of the soup's largest side, as
    // ReferenceScene::scene_size takes it.
    const glm::vec3 size = ctx.soup->bounds().size();
    const float largest = std::max({size.x, size.y, size.z});
    scene_size_ = largest > 0.0f && std::isfinite(largest) ? largest : 1.0f;
    has_dielectric_ = false;
    for (const Material& m : *ctx.host_materials)
      has_dielectric_ = has_dielectric_ || m.kind == MaterialKind::kDielectric;
  }

  void build(const FrameContext& ctx, const RenderOptions& options) override {
    VOXR_CHECK(ctx.triangle_grids != nullptr);
    grid_ = &ctx.triangle_grids->get(*ctx.mesh, options.shadow_resolution);
    ctx.stats->device_bytes = grid_->device_bytes();
  }

  void lookup(const FrameContext& ctx, const RenderOptions&, const cl::Buffer& ends,
              cl::Buffer& transmittance) override {
    cl::Kernel kernel = cl_.kernel("shadow_exact.cl", "shadow_exact", defines());
    cl_.launch("shadow_exact", kernel, ctx.pixels, kGroup, ends, cl_uint(ctx.pixels), *ctx.materials,
               cl_uint(ctx.material_count), *ctx.light, grid_->view_args(), scene_size_,
               cl_uint(has_dielectric_ ? 1 : 0), transmittance);
  }

  uint64_t device_bytes() const override { return grid_ ? grid_->device_bytes() : 0; }

  TechniqueDescription describe(const FrameStats& stats, const RenderOptions&) const override {
    TechniqueDescription d;
    if (!grid_) return d;
    const glm::uvec3 dims = grid_->grid().spec.dims;
    d.report["triangle_grid"] = {{"dims", {dims.x, dims.y, dims.z}}, {"device_bytes", stats.device_bytes}};
    d.lines.push_back(fmt::format("triangle grid {} x {} x {}, {:.1f} MiB", dims.x, dims.y, dims.z,
                                  double(stats.device_bytes) / (1 << 20)));
    return d;
  }

 private:
  static Defines defines() { return with(channel_defines(), "SHADOW_GROUP", std::to_string(kGroup)); }

  ClRuntime& cl_;
  Voxelizer& voxelizer_;
  TriangleGrid* grid_ = nullptr;  // the frame's, from ctx.triangle_grids (owned by FrameRenderer)
  float scene_size_ = 1.0f;
  bool has_dielectric_ = false;
};

}  // namespace

std::unique_ptr<ShadowTechnique> make_voxel_exact_shadows(ClRuntime& cl, Voxelizer& voxelizer) {
  return std::make_unique<VoxelExactShadows>(cl, voxelizer);
}

}  // namespace voxr
