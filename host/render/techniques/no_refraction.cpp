// No refraction: every pixel's path is the identity (voxr_layout.h) and its end is its primary sample, so
// dielectrics shade flat.
#include "render/technique.h"
#include "render/visibility_rasterizer.h"

namespace voxr {

namespace {

constexpr size_t kGroup = 64;

class NoRefraction final : public RefractionTechnique {
 public:
  explicit NoRefraction(ClRuntime&) {}
  std::vector<ProgramSpec> programs(const RenderOptions&) const override { return {{"refract_none.cl", {}}}; }
  bool writes_ends() const override { return false; }
  void trace(const FrameContext& ctx, const RenderOptions&, cl::Buffer&, cl::Buffer& paths) override {
    cl::Kernel identity = ctx.cl->kernel("refract_none.cl", "identity_paths");
    ctx.cl->launch("refraction", identity, ctx.pixels, kGroup, make_render_camera(*ctx.camera), paths);
  }
  uint64_t device_bytes() const override { return 0; }
  TechniqueDescription describe(const FrameStats&, const RenderOptions&) const override { return {}; }
};

}  // namespace

std::unique_ptr<RefractionTechnique> make_no_refraction(ClRuntime& cl) {
  return std::make_unique<NoRefraction>(cl);
}

}  // namespace voxr
