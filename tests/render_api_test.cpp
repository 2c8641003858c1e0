// voxr::render (include/voxr/render.h, libvoxr_render) against run_render_job, the function `voxr render`
// runs, and against the CLI's own .exr: the same pixels, bit for bit; bad settings throw voxr::Error.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <cstring>

#include "cli_support.h"
#include "eval/render_job.h"
#include "io/image_file.h"
#include "voxr/render.h"

namespace voxr {
namespace {

constexpr uint32_t kWidth = 40, kHeight = 30;

// The default scene at kWidth x kHeight through the public API.
const RenderedImage& api_image() {
  static const RenderedImage image = [] {
    RenderSettings s;
    s.width = kWidth;
    s.height = kHeight;
    return render(s);
  }();
  return image;
}

// Equal when every float has the same bits; the first differing pixel otherwise.
testing::AssertionResult same_pixels(const RenderedImage& api, const ImageRgba& image) {
  if (api.width != image.width || api.height != image.height)
    return testing::AssertionFailure()
           << "size " << api.width << "x" << api.height << " vs " << image.width << "x" << image.height;
  if (api.rgba.size() != image.pixels.size() * 4) return testing::AssertionFailure() << "rgba size";
  for (size_t i = 0; i < image.pixels.size(); ++i)
    if (std::memcmp(&api.rgba[i * 4], &image.pixels[i], 4 * sizeof(float)) != 0)
      return testing::AssertionFailure() << "pixel (" << i % image.width << ", " << i / image.width
                                         << ") differs: " << api.rgba[i * 4] << " vs " << image.pixels[i].x;
  return testing::AssertionSuccess();
}

// The public header spells the CLI's defaults out; they must stay the CLI's (RenderJob's).
TEST(RenderApi, DefaultsAreTheCliDefaults) {
  const RenderSettings s;
  const RenderJob job;
  EXPECT_EQ(s.refraction, job.refraction);
  EXPECT_EQ(s.shadows, job.shadows);
  EXPECT_EQ(s.shadow_res, job.shadow_res);
  EXPECT_EQ(s.res, job.res);
  EXPECT_EQ(s.mode, job.mode);
  EXPECT_EQ(s.bias, job.bias);
  EXPECT_EQ(s.normal_offset, job.normal_offset);
  EXPECT_EQ(s.refraction_grid, job.refraction_grid);
  EXPECT_EQ(s.coarse_res, job.coarse_res);
  EXPECT_EQ(s.step, job.step);
  EXPECT_EQ(s.normals, job.normals);
  EXPECT_EQ(s.angle_threshold, job.angle_threshold);
  EXPECT_EQ(s.layers, job.layers);
  EXPECT_EQ(s.layer_res, job.layer_res);
  EXPECT_EQ(s.dm_depth, 0u);  // 0: job.dm_depth
  EXPECT_EQ(s.frames, job.frames);
  EXPECT_EQ(s.error_target, job.error_target);
  EXPECT_EQ(s.compare_reference, job.compare_reference);
}

TEST(RenderApi, SamePixelsAsTheCliJob) {
  RenderJob job;
  job.size = {kWidth, kHeight};
  const RenderJobResult cli = run_render_job(job);
  const RenderedImage& api = api_image();
  EXPECT_TRUE(same_pixels(api, cli.image));
  // The same report but for the times.
  nlohmann::json a = nlohmann::json::parse(api.report_json), b = cli.report;
  for (nlohmann::json* r : {&a, &b}) {
    r->erase("ms");
    r->erase("frames");
    r->erase("fps_rendered");
  }
  EXPECT_EQ(a, b);
  EXPECT_EQ(a["size"], nlohmann::json({kWidth, kHeight}));
}

TEST(RenderApi, SamePixelsAsTheCliExr) {
  const auto out = test::scratch() / "render_api.exr";
  const test::CliResult r = test::run_voxr("render --size " + std::to_string(kWidth) + "x" +
                                           std::to_string(kHeight) + " -q -o " + out.string());
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(same_pixels(api_image(), read_image(out)));
}

TEST(RenderApi, BadSettingsThrowVoxrErrors) {
  RenderSettings s;
  s.width = kWidth;
  s.height = kHeight;
  s.scene = "/no/such/scene.json";
  try {
    render(s);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()), "/no/such/scene.json: no such file");
  }
  s.scene.clear();
  s.shadows = "sideways";
  EXPECT_THROW(render(s), Error);
  s.shadows.clear();
  s.layers = 8;  // distance-maps only
  try {
    render(s);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("--layers applies to --refraction distance-maps only"),
              std::string::npos)
        << e.what();
  }
  s.layers = 4;
  s.width = 0;  // one side only
  EXPECT_THROW(render(s), Error);
}

}  // namespace
}  // namespace voxr
