// Refraction `voxel-exact` (issue 19 item 2; beyond the papers): the matched reference's path model on the
// exact triangles, found through the per-voxel triangle lists (render/triangle_grid.h) rebuilt every frame
// on the device from the conservative voxelizer; kernels/render/refraction/refract_exact.cl marches them.
// The grid resolution (--res) is a speed knob only: the hits are the triangles' own at any resolution.
#include <fmt/format.h>

#include <algorithm>

#include "grid/channel_table.h"
#include "render/technique.h"
#include "render/triangle_grid.h"
#include "render/visibility_rasterizer.h"
#include "util/error.h"
#include "voxelize/voxelizer.h"

namespace voxr {

namespace {

constexpr size_t kGroup = 64;
// Hits closer than this along a ray, relative to the mesh's largest side, are one meeting of the ray with
// coincident surfaces, ordered by material (opaque first) and triangle id (triangle_grid.h tg_better).
constexpr float kCoincide = 1e-5f;

Defines exact_defines() {
  Defines d = channel_defines();
  d.push_back({"PATH_GROUP", std::to_string(kGroup)});
  return d;
}

class VoxelExactRefraction final : public RefractionTechnique {
 public:
  VoxelExactRefraction(ClRuntime& cl, Voxelizer& voxelizer) : cl_(cl), voxelizer_(voxelizer) {}

  std::vector<ProgramSpec> programs(const RenderOptions&) const override {
    std::vector<ProgramSpec> specs = TriangleGrid::programs();
    specs.push_back({"refract_exact.cl", exact_defines()});
    return specs;
  }
  void prepare(const RenderOptions&) override { voxelizer_.prepare(TriangleGrid::voxelize_options()); }
  bool writes_ends() const override { return true; }

  void trace(const FrameContext& ctx, const RenderOptions& options, cl::Buffer& ends,
             cl::Buffer& paths) override {
    VOXR_CHECK(ctx.triangle_grids != nullptr);
    VOXR_CHECK(ctx.material_count > 0);
    TriangleGrid& grid = ctx.triangle_grids->get(*ctx.mesh, options.refraction.resolution);
    const Bounds& b = ctx.mesh->bounds();
    const glm::vec3 extent = b.hi - b.lo;
    const float coincide = kCoincide * std::max({extent.x, extent.y, extent.z, 1e-30f});
    cl::Kernel kernel = cl_.kernel("refract_exact.cl", "refract_exact", exact_defines());
    cl_.launch("refraction", kernel, ctx.dielectric->pixel_count(), kGroup, grid.view_args(),
               make_render_camera(*ctx.camera), *ctx.primary_samples, *ctx.dielectric, *ctx.materials,
               cl_uint(ctx.material_count), *ctx.vertex_normals, coincide, ends, paths);
    ctx.stats->refraction_grid = grid.grid().spec;
    ctx.stats->refraction_bytes = grid.device_bytes();
    bytes_ = grid.device_bytes();
  }

  uint64_t device_bytes() const override { return bytes_; }

  TechniqueDescription describe(const FrameStats& stats, const RenderOptions& options) const override {
    const glm::uvec3 d = stats.refraction_grid.dims;
    TechniqueDescription out;
    out.suffix = fmt::format(" (triangle lists on grid {}x{}x{}, {:.1f} MiB)", d.x, d.y, d.z,
                             double(stats.refraction_bytes) / (1 << 20));
    out.report["refraction_options"] = {{"res", options.refraction.resolution}};
    out.report["refraction_grid"] = {{"dims", {d.x, d.y, d.z}},
                                     {"voxel_size", stats.refraction_grid.voxel_size},
                                     {"device_bytes", stats.refraction_bytes},
                                     {"kind", "triangle lists"}};
    return out;
  }

 private:
  ClRuntime& cl_;
  Voxelizer& voxelizer_;
  uint64_t bytes_ = 0;
};

}  // namespace

std::unique_ptr<RefractionTechnique> make_voxel_exact_refraction(ClRuntime& cl, Voxelizer& voxelizer) {
  return std::make_unique<VoxelExactRefraction>(cl, voxelizer);
}

}  // namespace voxr
