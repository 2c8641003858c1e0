// Environment maps (render/environment_map.h, kernels/common/environment.h): the lat-long convention,
// bilinear lookups, the procedural checker, images read through OpenImageIO (.exr, .hdr, .png) with one-line
// errors, and the scene keys that choose them.
#include <gtest/gtest.h>

#include <OpenImageIO/imageio.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include "core/scene.h"
#include "io/image_file.h"
#include "render/environment_map.h"
#include "test_support.h"
#include "util/error.h"

namespace voxr {
namespace {

namespace fs = std::filesystem;

// A 4 x 2 image whose texel (x, y) has red x, green y: row 0 is the upper hemisphere.
EnvironmentMap ramp() {
  std::vector<glm::vec4> px;
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < 4; ++x) px.emplace_back(float(x), float(y), 1.0f, 1.0f);
  return EnvironmentMap::from_pixels(4, 2, px, "ramp");
}

TEST(EnvironmentMap, LatLongConvention) {
  const EnvironmentMap m = ramp();
  // -z is the image's centre column (u = 0.5: between texels 1 and 2), +x three quarters along (u = 0.75, the
  // centre of texel 2 + 0.5), straight up and down the top and bottom rows.
  EXPECT_NEAR(m.lookup({0, 0, -1}).x, 1.5f, 1e-5f);
  EXPECT_NEAR(m.lookup({1, 0, 0}).x, 2.5f, 1e-5f);
  EXPECT_NEAR(m.lookup({0, 1, 0}).y, 0.0f, 1e-5f);
  EXPECT_NEAR(m.lookup({0, -1, 0}).y, 1.0f, 1e-5f);
  EXPECT_NEAR(m.lookup({0, 0, -1}).y, 0.5f, 1e-5f);  // the horizon: halfway between the rows
  // Wrapping in u: +z (u = 0 = 1) blends the last and the first column.
  EXPECT_NEAR(m.lookup({0, 0, 1}).x, 1.5f, 1e-5f);  // (3 + 0) / 2
  // Direction length does not matter; a zero direction looks up.
  EXPECT_EQ(m.lookup({0, 0, -7}), m.lookup({0, 0, -1}));
  EXPECT_NEAR(m.lookup({0, 0, 0}).y, 0.0f, 1e-5f);
}

TEST(EnvironmentMap, ConstantAndMean) {
  const EnvironmentMap c = EnvironmentMap::constant({0.2f, 0.4f, 0.6f});
  EXPECT_EQ(c.lookup({0.3f, -0.2f, 0.9f}), glm::vec3(0.2f, 0.4f, 0.6f));
  EXPECT_NEAR(c.mean().y, 0.4f, 1e-6f);
  // The mean weights rows by solid angle: a map bright only in its top row (the polar cap, 1 - cos(45)) of
  // two rows has mean (1 - cos 90) / 2 of the sphere's = 0.5.
  std::vector<glm::vec4> px = {glm::vec4(1.0f), glm::vec4(1.0f), glm::vec4(0.0f, 0.0f, 0.0f, 1.0f),
                               glm::vec4(0.0f, 0.0f, 0.0f, 1.0f)};
  EXPECT_NEAR(EnvironmentMap::from_pixels(2, 2, px, "cap").mean().x, 0.5f, 1e-6f);
}

TEST(EnvironmentMap, CheckerTellsDirectionsApart) {
  const EnvironmentMap m = EnvironmentMap::checker();
  EXPECT_EQ(m.width(), 2 * m.height());
  // Neighbouring cells (11.25 degrees apart) differ; the lower hemisphere is darker.
  const auto dir = [](float azimuth_deg, float elevation_deg) {
    const float a = glm::radians(azimuth_deg), e = glm::radians(elevation_deg);
    return glm::vec3(std::sin(a) * std::cos(e), std::sin(e), -std::cos(a) * std::cos(e));
  };
  EXPECT_GT(glm::length(m.lookup(dir(5, 30)) - m.lookup(dir(17, 30))), 0.1f);
  EXPECT_GT(glm::length(m.lookup(dir(5, 30)) - m.lookup(dir(5, 42))), 0.1f);
  EXPECT_LT(m.lookup(dir(5, -30)).x + m.lookup(dir(5, -30)).y,
            m.lookup(dir(5, 30)).x + m.lookup(dir(5, 30)).y);
}

TEST(EnvironmentMap, BadPixelsNameTheSource) {
  std::vector<glm::vec4> px = {glm::vec4(1.0f), glm::vec4(-1.0f, 0.0f, 0.0f, 1.0f)};
  try {
    EnvironmentMap::from_pixels(2, 1, px, "sky.exr");
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_STREQ(e.what(), "sky.exr: environment texel (1, 0) has radiance -1 (must be finite and >= 0)");
  }
  EXPECT_THROW(EnvironmentMap::from_pixels(0, 1, {}, "x"), Error);
  EXPECT_THROW(EnvironmentMap::from_pixels(2, 2, px, "x"), Error);
}

void write_hdr(const fs::path& path, const ImageRgba& image) {
  std::unique_ptr<OIIO::ImageOutput> out = OIIO::ImageOutput::create(path.string());
  ASSERT_TRUE(out);
  std::vector<float> rgb;
  for (const glm::vec4& p : image.pixels) rgb.insert(rgb.end(), {p.x, p.y, p.z});
  OIIO::ImageSpec spec(int(image.width), int(image.height), 3, OIIO::TypeDesc::FLOAT);
  ASSERT_TRUE(out->open(path.string(), spec));
  ASSERT_TRUE(out->write_image(OIIO::TypeDesc::FLOAT, rgb.data()));
  out->close();
}

TEST(EnvironmentMap, ImagesFromSceneFiles) {
  const fs::path dir = fs::path(VOXR_BINARY_DIR) / "environment-map-test";
  fs::create_directories(dir);
  ImageRgba image(8, 4, glm::vec4(0.25f, 0.5f, 2.0f, 1.0f));
  image.at(5, 1) = glm::vec4(4.0f, 0.0f, 0.0f, 1.0f);
  write_image(image, dir / "sky.exr");
  write_hdr(dir / "sky.hdr", image);
  ImageRgba ldr(8, 4, glm::vec4(0.5f, 0.5f, 0.5f, 1.0f));
  write_image(ldr, dir / "sky.png");
  const std::string box = R"("meshes": [{"generator": "box"}])";
  for (const char* name : {"sky.exr", "sky.hdr"}) {
    const Scene s = parse_scene("{" + box + R"(, "environment": {"image": ")" + name + "\"}}", "s.json", dir);
    EXPECT_EQ(s.environment.image, (dir / name).string());
    const EnvironmentMap m = make_environment_map(s.environment);
    EXPECT_EQ(m.width(), 8u);
    EXPECT_NEAR(m.lookup({0, 0, -1}).z, 2.0f, 1e-3f) << name;  // HDR values survive
  }
  const Scene png = parse_scene("{" + box + R"(, "environment": {"image": "sky.png"}})", "s.json", dir);
  EXPECT_NEAR(make_environment_map(png.environment).lookup({0, 0, -1}).x, 0.5f, 0.01f);  // decoded from sRGB
  try {
    parse_scene("{" + box + R"(, "environment": {"image": "nowhere.exr"}})", "s.json", dir);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("'environment.image' names"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("nowhere.exr"), std::string::npos) << e.what();
  }
  std::ofstream(dir / "notes.txt") << "not an image";
  Environment text;
  text.image = (dir / "notes.txt").string();
  try {
    make_environment_map(text);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("unsupported environment image format '.txt'"), std::string::npos);
  }
}

}  // namespace
}  // namespace voxr
