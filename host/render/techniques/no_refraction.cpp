// No refraction: every pixel's path is the identity (voxr_layout.h) and its end is its primary sample, so
// dielectrics shade flat. Nothing runs: the frame has no refraction stage and shades the primary samples.
#include "render/technique.h"

namespace voxr {

namespace {

class NoRefraction final : public RefractionTechnique {
 public:
  explicit NoRefraction(ClRuntime&) {}
  std::vector<ProgramSpec> programs(const RenderOptions&) const override { return {}; }
  bool writes_ends() const override { return false; }
  void trace(const FrameContext&, const RenderOptions&, cl::Buffer&, cl::Buffer&) override {}
  uint64_t device_bytes() const override { return 0; }
  TechniqueDescription describe(const FrameStats&, const RenderOptions&) const override { return {}; }
};

}  // namespace

std::unique_ptr<RefractionTechnique> make_no_refraction(ClRuntime& cl, Voxelizer&) {
  return std::make_unique<NoRefraction>(cl);
}

}  // namespace voxr
