// The render regression harness itself (render_regression.h): pass, fail with the three images written,
// missing references, update mode.
#include "render_regression.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <optional>
#include <string>

#include "io/image_file.h"
#include "test_support.h"

namespace voxr::test {
namespace {

// A 96x72 colour gradient, the size references are kept at.
ImageRgba gradient() {
  ImageRgba image(96, 72);
  for (uint32_t y = 0; y < image.height; ++y)
    for (uint32_t x = 0; x < image.width; ++x)
      image.at(x, y) = glm::vec4(float(x) / 95.0f, float(y) / 71.0f, 0.25f + 0.5f * float((x + y) % 2), 1.0f);
  return image;
}

// A reference folder and a scratch folder of the test's own, and no update mode whatever the caller's
// environment says.
struct Fixture {
  TempDir dir;
  RegressionFolders folders{dir.path() / "references", dir.path() / "scratch"};
  ScopedEnv no_update{"VOXR_UPDATE_REFERENCES", std::nullopt};

  void store(const ImageRgba& image, const std::string& name) const {
    fs::create_directories(folders.references);
    write_image(image, folders.references / (name + ".exr"));
  }
  bool scratch_has(const std::string& file) const { return fs::exists(folders.scratch / file); }
};

TEST(RenderRegression, IdenticalImagePasses) {
  const Fixture f;
  f.store(gradient(), "gradient");
  EXPECT_TRUE(matches_reference(gradient(), "gradient", {}, f.folders));
  EXPECT_FALSE(fs::exists(f.folders.scratch)) << "nothing written on success";
}

TEST(RenderRegression, DifferencesWithinTolerancePass) {
  const Fixture f;
  f.store(gradient(), "gradient");
  ImageRgba image = gradient();
  image.at(10, 20).x += 0.04f;  // under the default pixel threshold 0.05
  image.at(11, 20).y += 0.5f;   // one pixel over it: 1/6912 = 0.014%, under the default 1%
  EXPECT_TRUE(matches_reference(image, "gradient", {}, f.folders));
}

TEST(RenderRegression, ChangedPixelFailsAndWritesThreeImages) {
  const Fixture f;
  f.store(gradient(), "gradient");
  ImageRgba image = gradient();
  image.at(30, 40).y += 0.5f;
  RegressionTolerance strict;
  strict.max_share_over = 0.0;
  const ::testing::AssertionResult result = matches_reference(image, "gradient", strict, f.folders);
  ASSERT_FALSE(result);
  const std::string message = result.message();
  EXPECT_NE(message.find("1 of 6912 pixels"), std::string::npos) << message;
  EXPECT_NE(message.find("largest difference 0.5 at pixel (30, 40)"), std::string::npos) << message;
  EXPECT_NE(message.find(f.folders.scratch.string()), std::string::npos) << message;
  EXPECT_NE(message.find("VOXR_UPDATE_REFERENCES=1"), std::string::npos) << message;
  for (const char* kind : {"actual", "reference", "difference"})
    for (const char* ext : {".exr", ".png"})
      EXPECT_TRUE(f.scratch_has(std::string("gradient.") + kind + ext)) << kind << ext;
  // The files hold what they say; the difference is scaled so that its largest value is 1.
  EXPECT_EQ(read_image(f.folders.scratch / "gradient.actual.exr").pixels, image.pixels);
  EXPECT_EQ(read_image(f.folders.scratch / "gradient.reference.exr").pixels, gradient().pixels);
  const ImageRgba difference = read_image(f.folders.scratch / "gradient.difference.exr");
  for (uint32_t y = 0; y < difference.height; ++y)
    for (uint32_t x = 0; x < difference.width; ++x)
      ASSERT_EQ(difference.at(x, y), x == 30 && y == 40 ? glm::vec4(0, 1, 0, 1) : glm::vec4(0, 0, 0, 1))
          << x << ", " << y;

  // An RMSE over its limit fails on its own too; a later pass clears the scratch files.
  RegressionTolerance tight;
  tight.max_rmse = 1e-4;
  tight.pixel_threshold = 1.0;
  EXPECT_FALSE(matches_reference(image, "gradient", tight, f.folders));
  EXPECT_TRUE(matches_reference(gradient(), "gradient", strict, f.folders));
  EXPECT_FALSE(f.scratch_has("gradient.actual.exr"));
  EXPECT_FALSE(f.scratch_has("gradient.difference.png"));
}

TEST(RenderRegression, MissingReferenceSaysHowToCreateIt) {
  const Fixture f;
  const ::testing::AssertionResult result = matches_reference(gradient(), "new_scene", {}, f.folders);
  ASSERT_FALSE(result);
  const std::string message = result.message();
  EXPECT_NE(message.find("no reference image " + (f.folders.references / "new_scene.exr").string()),
            std::string::npos)
      << message;
  EXPECT_NE(message.find("VOXR_UPDATE_REFERENCES=1"), std::string::npos) << message;
  EXPECT_TRUE(f.scratch_has("new_scene.actual.exr"));
}

TEST(RenderRegression, UpdateModeWritesTheReference) {
  const Fixture f;
  {
    const ScopedEnv update("VOXR_UPDATE_REFERENCES", "1");
    EXPECT_TRUE(matches_reference(gradient(), "gradient", {}, f.folders));
  }
  const fs::path written = f.folders.references / "gradient.exr";
  ASSERT_TRUE(fs::exists(written));
  EXPECT_EQ(read_image(written).pixels, gradient().pixels);
  // Rewritten from a changed image, after which the changed image is the one that matches.
  ImageRgba changed = gradient();
  changed.at(0, 0) = glm::vec4(1.0f);
  EXPECT_FALSE(matches_reference(changed, "gradient", {.max_share_over = 0.0}, f.folders));
  {
    const ScopedEnv update("VOXR_UPDATE_REFERENCES", "1");
    EXPECT_TRUE(matches_reference(changed, "gradient", {}, f.folders));
  }
  EXPECT_TRUE(matches_reference(changed, "gradient", {.max_share_over = 0.0}, f.folders));
}

TEST(RenderRegression, RefusesBadImagesAndNames) {
  const Fixture f;
  f.store(gradient(), "gradient");
  // Size mismatch.
  const ::testing::AssertionResult small = matches_reference(ImageRgba(48, 36), "gradient", {}, f.folders);
  ASSERT_FALSE(small);
  EXPECT_NE(std::string(small.message()).find("the image is 48x36, the reference"), std::string::npos)
      << small.message();
  // NaN, even where the tolerance would let any value through; also in update mode.
  ImageRgba nan = gradient();
  nan.at(5, 5).z = std::nanf("");
  const RegressionTolerance anything{1e9, 1e9, 1.0};
  const ::testing::AssertionResult bad = matches_reference(nan, "gradient", anything, f.folders);
  ASSERT_FALSE(bad);
  EXPECT_NE(std::string(bad.message()).find("1 NaN or infinite values"), std::string::npos) << bad.message();
  {
    const ScopedEnv update("VOXR_UPDATE_REFERENCES", "1");
    EXPECT_FALSE(matches_reference(nan, "gradient", {}, f.folders));
  }
  EXPECT_TRUE(matches_reference(gradient(), "gradient", {}, f.folders)) << "reference kept";
  EXPECT_FALSE(matches_reference(gradient(), "../gradient", {}, f.folders));
  EXPECT_FALSE(matches_reference(gradient(), "", {}, f.folders));
  EXPECT_FALSE(matches_reference(ImageRgba(), "gradient", {}, f.folders));
}

}  // namespace
}  // namespace voxr::test
