// The Embree refraction references as a technique (reference/reference_refraction.h, through SceneReference):
// reference (matched: the refracted path only, the device methods' model) and reference-full (Whitted's
// reflection and refraction tree, exact Fresnel). Both render the finished frame on the host, shaded with the
// exact shadows; the reference's BVH is built on first need, inside the frame.
#include "render/technique.h"
#include "util/clock.h"
#include "util/error.h"

namespace voxr {

namespace {

class ReferenceRefraction final : public RefractionTechnique {
 public:
  explicit ReferenceRefraction(ClRuntime&) {}
  std::vector<ProgramSpec> programs(const RenderOptions&) const override { return {}; }
  bool writes_ends() const override { return true; }
  void trace(const FrameContext&, const RenderOptions&, cl::Buffer&, cl::Buffer&) override {
    throw InternalError("the reference refraction renders on the host (render_on_host)");
  }
  bool finishes_on_host() const override { return true; }

  HostFrame render_on_host(const FrameContext& ctx, const RenderOptions& options) override {
    SceneReference& reference = ctx.need_reference("the reference refraction");
    const auto start = Clock::now();
    HostRefraction r = reference.refraction(*ctx.light, *ctx.environment, *ctx.camera,
                                            options.refraction.method == RefractionMethod::kReferenceFull);
    ctx.stats->host_ms += ms_since(start);
    ctx.stats->stage_ms["bvh_build"] = r.bvh_build_ms;
    ctx.stats->stage_ms["trace"] = r.trace_ms;
    ctx.stats->stage_ms["shadow"] = r.shadow_ms;
    ctx.stats->stage_ms["shade"] = r.shade_ms;
    return {std::move(r.image), std::move(r.ends), std::move(r.paths), std::move(r.transmittance)};
  }

  uint64_t device_bytes() const override { return 0; }
  TechniqueDescription describe(const FrameStats&, const RenderOptions&) const override { return {}; }
};

}  // namespace

std::unique_ptr<RefractionTechnique> make_reference_refraction(ClRuntime& cl, Voxelizer&) {
  return std::make_unique<ReferenceRefraction>(cl);
}

}  // namespace voxr
