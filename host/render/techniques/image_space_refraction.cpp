// Image-space refraction (render/image_space_refraction.h; Wyman 2005, SIGGRAPH, with nearby geometry,
// GRAPHITE 2005). Per scene: d_N per vertex, ray cast by the exact reference as the paper precomputes it
// offline (§3). Per frame: back faces and opaque surfaces rasterized, two refractions per pixel.
#include "render/image_space_refraction.h"
#include "render/technique.h"
#include "render/visibility_rasterizer.h"
#include "util/clock.h"

namespace voxr {

namespace {

class ImageSpaceTechnique final : public RefractionTechnique {
 public:
  explicit ImageSpaceTechnique(ClRuntime& cl) : rasterizer_(cl), refraction_(cl, rasterizer_) {}

  std::vector<ProgramSpec> programs(const RenderOptions&) const override {
    std::vector<ProgramSpec> specs = rasterizer_.programs();
    for (const ProgramSpec& p : refraction_.programs()) specs.push_back(p);
    return specs;
  }

  void set_scene(const FrameContext& ctx) override {
    refraction_.set_inward_distances(
        ctx.need_reference("image-space refraction (d_N)").inward_distances(*ctx.host_normals));
  }

  bool writes_ends() const override { return true; }

  void trace(const FrameContext& ctx, const RenderOptions&, cl::Buffer& ends, cl::Buffer& paths) override {
    refraction_.trace(*ctx.mesh, *ctx.vertex_normals, *ctx.camera, *ctx.materials, ctx.material_count,
                      *ctx.primary_samples, *ctx.dielectric, ends, paths);
    ctx.stats->refraction_bytes = refraction_.device_bytes();
  }

  uint64_t device_bytes() const override { return refraction_.device_bytes(); }
  TechniqueDescription describe(const FrameStats&, const RenderOptions&) const override { return {}; }

 private:
  VisibilityRasterizer rasterizer_;
  ImageSpaceRefraction refraction_;
};

}  // namespace

std::unique_ptr<RefractionTechnique> make_image_space_refraction(ClRuntime& cl, Voxelizer&) {
  return std::make_unique<ImageSpaceTechnique>(cl);
}

}  // namespace voxr
