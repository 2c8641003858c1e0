// The exact shadows as a technique: the path ends are read back and the SceneReference (Embree shadow rays
// through every surface, straight; reference/reference_renderer.h) gives their transmittance, which is
// uploaded for shading. The reference's BVH is built on first need, inside the frame (host_ms).
#include "render/technique.h"
#include "util/clock.h"

namespace voxr {

namespace {

class ReferenceShadows final : public ShadowTechnique {
 public:
  explicit ReferenceShadows(ClRuntime&) {}
  std::vector<ProgramSpec> programs(const RenderOptions&) const override { return {}; }
  void build(const FrameContext&, const RenderOptions&) override {}

  void lookup(const FrameContext& ctx, const RenderOptions&, const cl::Buffer& ends,
              cl::Buffer& transmittance) override {
    SceneReference& reference = ctx.need_reference("the reference shadows");
    ClRuntime& cl = *ctx.cl;
    std::vector<SurfaceSample> samples(ctx.pixels);
    cl.download(ends, samples.data(), ctx.pixels * sizeof(SurfaceSample), "download samples");
    cl.finish("resolving the camera's samples");
    const auto host_start = Clock::now();
    const std::vector<glm::vec3> t = reference.transmittance(*ctx.light, samples);
    ctx.stats->host_ms += ms_since(host_start);
    std::vector<glm::vec4> t4(ctx.pixels);
    for (size_t i = 0; i < ctx.pixels; ++i) t4[i] = glm::vec4(t[i], 1.0f);
    cl.upload(transmittance, t4.data(), ctx.pixels * sizeof(glm::vec4), "upload reference transmittance");
  }

  uint64_t device_bytes() const override { return 0; }
  TechniqueDescription describe(const FrameStats&, const RenderOptions&) const override { return {}; }
};

}  // namespace

std::unique_ptr<ShadowTechnique> make_reference_shadows(ClRuntime& cl, Voxelizer&) {
  return std::make_unique<ReferenceShadows>(cl);
}

}  // namespace voxr
