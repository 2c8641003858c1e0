// Refraction only where a pixel sees a dielectric (render/dielectric_pixels.h): the list kernel against a
// host count of the same samples, a frame of a scene without dielectrics (no refraction stage, identity
// paths), and a glass frame whose other pixels are exactly the frame without refraction.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <vector>

#include "refraction_ball.h"
#include "render/dielectric_pixels.h"
#include "render/environment_map.h"
#include "render/frame_renderer.h"
#include "render/render_scene.h"
#include "render/shade_host.h"
#include "test_support.h"

namespace voxr {
namespace {

using namespace test::ball;

// The host twin against the device's shading: the device's rsqrt and float evaluation order.
constexpr float kTwinTolerance = 1e-4f;

bool same_bytes(const SurfaceSample& a, const SurfaceSample& b) {
  return std::memcmp(&a, &b, sizeof(SurfaceSample)) == 0;
}
bool same_bytes(const RefractionPath& a, const RefractionPath& b) {
  return std::memcmp(&a, &b, sizeof(RefractionPath)) == 0;
}

TEST(DielectricPixels, ListsExactlyThePixelsThatSeeADielectric) {
  ClRuntime& cl = test::runtime();
  cl.build_programs({DielectricPixels::program()});
  RenderMaterial opaque{}, glass{}, sheet{};
  opaque.kind = VOXR_MATERIAL_OPAQUE;
  glass.kind = VOXR_MATERIAL_DIELECTRIC;
  sheet.kind = VOXR_MATERIAL_SHEET;
  const std::vector<RenderMaterial> materials = {opaque, glass, sheet};
  // Not a multiple of the group size; misses, every material and an id past the last (clamped: a sheet).
  constexpr uint32_t kPixels = 1001;
  std::vector<SurfaceSample> primary(kPixels);
  std::vector<uint32_t> expected;
  for (uint32_t i = 0; i < kPixels; ++i) {
    SurfaceSample& s = primary[i];
    s = SurfaceSample{};
    s.position[0] = float(i);
    s.distance = 0.5f * float(i);
    s.triangle = i % 7 == 0 ? VOXR_NO_TRIANGLE : i;
    s.material = i % 11 == 5 ? 9u : (i * 13u) % 3u;
    if (s.triangle != VOXR_NO_TRIANGLE && s.material == 1u) expected.push_back(i);
  }
  ASSERT_GT(expected.size(), 200u);
  cl::Buffer primary_buffer = cl.buffer(kPixels * sizeof(SurfaceSample), "primary");
  cl.upload(primary_buffer, primary.data(), kPixels * sizeof(SurfaceSample), "upload primary");
  cl::Buffer material_buffer = cl.buffer(materials.size() * sizeof(RenderMaterial), "materials");
  cl.upload(material_buffer, materials.data(), materials.size() * sizeof(RenderMaterial), "upload materials");
  SurfaceSample canary;
  std::memset(&canary, 0xab, sizeof canary);
  const std::vector<SurfaceSample> canaries(kPixels, canary);
  cl::Buffer ends = cl.buffer(kPixels * sizeof(SurfaceSample), "ends");

  DielectricPixels pixels(cl);
  for (int run = 0; run < 2; ++run) {  // the count starts from zero every time
    cl.upload(ends, canaries.data(), kPixels * sizeof(SurfaceSample), "upload canaries");
    pixels.find(primary_buffer, kPixels, material_buffer, uint32_t(materials.size()), ends);
    EXPECT_EQ(pixels.pixel_count(), kPixels);
    uint32_t count = 0;
    cl.download(pixels.count(), &count, sizeof count, "download count");
    std::vector<uint32_t> list(kPixels);
    cl.download(pixels.list(), list.data(), kPixels * sizeof(uint32_t), "download list");
    std::vector<SurfaceSample> out(kPixels);
    cl.download(ends, out.data(), kPixels * sizeof(SurfaceSample), "download ends");
    cl.finish("listing dielectric pixels");
    ASSERT_EQ(count, expected.size());
    list.resize(count);
    std::sort(list.begin(), list.end());
    EXPECT_EQ(list, expected);
    size_t wrong = 0;
    for (uint32_t i = 0; i < kPixels; ++i) {
      const bool listed = std::binary_search(expected.begin(), expected.end(), i);
      wrong += !same_bytes(out[i], listed ? canary : primary[i]);  // listed ends: left to the refraction
    }
    EXPECT_EQ(wrong, 0u);
  }
}

// The ball scene through a FrameRenderer with the checker environment: a frame by `options` with its stats.
class BallFrames {
 public:
  explicit BallFrames(std::vector<Material> materials)
      : materials_(std::move(materials)), soup_(scene(true)) {
    renderer_.set_scene(soup_, materials_);
    renderer_.set_environment(EnvironmentMap::checker());
  }
  RenderedFrame render(RefractionMethod method, bool keep_samples, FrameStats* stats = nullptr) {
    RenderOptions o;
    o.shadows = ShadowMethod::kVoxel;
    o.shadow_resolution = 64;
    o.refraction.method = method;
    o.refraction.resolution = 128;
    o.keep_samples = keep_samples;
    renderer_.prepare(o);
    return renderer_.render(light(), camera(), o, stats);
  }
  const std::vector<Material>& materials() const { return materials_; }

 private:
  std::vector<Material> materials_;
  TriangleSoup soup_;
  FrameRenderer renderer_{test::runtime()};
};

TEST(DielectricPixels, ASceneWithoutDielectricsRunsNoRefraction) {
  std::vector<Material> mats = test::ball::materials();
  mats[kGlass].kind = MaterialKind::kOpaque;  // the ball is opaque: nothing to refract
  BallFrames frames(mats);
  FrameStats stats;
  const RenderedFrame multi = frames.render(RefractionMethod::kVoxelMulti, false, &stats);
  EXPECT_EQ(stats.stage_ms.count("refraction"), 0u);
  EXPECT_EQ(stats.stage_ms.count("dielectric pixels"), 0u);
  EXPECT_EQ(stats.stage_ms.count("shade"), 1u);
  EXPECT_EQ(stats.refraction_bytes, 0u);

  // The image is the host twin's of the primary samples and every pixel's identity path.
  const RenderedFrame kept = frames.render(RefractionMethod::kNone, true);
  ASSERT_EQ(kept.paths.size(), size_t(kWidth) * kHeight);
  size_t misses = 0;
  for (size_t i = 0; i < kept.paths.size(); ++i) {
    EXPECT_EQ(kept.paths[i].events, 0u);
    misses += kept.samples[i].triangle == VOXR_NO_TRIANGLE;
  }
  EXPECT_GT(misses, 1000u);  // the environment around the ball, shaded in the camera ray's direction
  const ImageRgba host =
      shade_paths(kept.samples, kept.transmittance, kept.paths, render_materials(frames.materials()), light(),
                  EnvironmentMap::checker(), kWidth, kHeight);
  EXPECT_EQ(multi.image.pixels, kept.image.pixels);
  for (size_t i = 0; i < host.pixels.size(); ++i)
    for (int c = 0; c < 3; ++c)
      ASSERT_NEAR(multi.image.pixels[i][c], host.pixels[i][c], kTwinTolerance)
          << "pixel " << i << " channel " << c;
}

TEST(DielectricPixels, AGlassFrameTracesOnlyThePixelsThatSeeIt) {
  BallFrames frames(test::ball::materials());
  const RenderedFrame plain = frames.render(RefractionMethod::kNone, true);
  for (RefractionMethod method : {RefractionMethod::kVoxelMulti, RefractionMethod::kDistanceMaps}) {
    FrameStats stats;
    const RenderedFrame refracted = frames.render(method, true, &stats);
    SCOPED_TRACE(refraction_method_info(method).name);
    EXPECT_EQ(stats.stage_ms.count("dielectric pixels"), 1u);
    EXPECT_EQ(stats.stage_ms.count("refraction"), 1u);
    size_t glass = 0, wrong = 0;
    for (size_t i = 0; i < plain.samples.size(); ++i) {
      if (plain.samples[i].triangle != VOXR_NO_TRIANGLE && plain.samples[i].material == kGlass) {
        ++glass;
        wrong += refracted.paths[i].events == 0u;  // traced: at least the front surface
        continue;
      }
      // Every other pixel: its primary sample, identity path and colour, to the bit.
      wrong += !same_bytes(refracted.samples[i], plain.samples[i]) ||
               !same_bytes(refracted.paths[i], plain.paths[i]) ||
               refracted.image.pixels[i] != plain.image.pixels[i];
    }
    EXPECT_GT(glass, 1000u);
    EXPECT_EQ(wrong, 0u);
    // The kept arrays are every pixel's: the host twin shades them to the device's image.
    const ImageRgba host = shade_paths(refracted.samples, refracted.transmittance, refracted.paths,
                                       render_materials(frames.materials()), light(),
                                       EnvironmentMap::checker(), kWidth, kHeight);
    for (size_t i = 0; i < host.pixels.size(); ++i)
      for (int c = 0; c < 3; ++c)
        ASSERT_NEAR(refracted.image.pixels[i][c], host.pixels[i][c], kTwinTolerance)
            << "pixel " << i << " channel " << c;
  }
}

}  // namespace
}  // namespace voxr
