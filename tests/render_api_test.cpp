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
