// No shadows: every receiver fully lit (transmittance 1), no light-space structure.
#include "render/technique.h"

namespace voxr {

namespace {

class NoShadows final : public ShadowTechnique {
 public:
  explicit NoShadows(ClRuntime&) {}
  std::vector<ProgramSpec> programs(const RenderOptions&) const override { return {}; }
  void build(const FrameContext&, const RenderOptions&) override {}
  void lookup(const FrameContext& ctx, const RenderOptions&, const cl::Buffer&,
              cl::Buffer& transmittance) override {
    const glm::vec4 one(1.0f);
    ctx.cl->queue().enqueueFillBuffer(transmittance, one, 0, ctx.pixels * sizeof(glm::vec4));
  }
  uint64_t device_bytes() const override { return 0; }
  TechniqueDescription describe(const FrameStats&, const RenderOptions&) const override { return {}; }
};

}  // namespace

std::unique_ptr<ShadowTechnique> make_no_shadows(ClRuntime& cl, Voxelizer&) {
  return std::make_unique<NoShadows>(cl);
}

}  // namespace voxr
