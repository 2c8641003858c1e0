// PNG and EXR files (io/image_file.h): EXR keeps linear floats exactly, PNG stores sRGB-encoded 8-bit colour
// and decodes back within a quantization step, OpenImageIO (an independent reader and writer) agrees both
// ways, errors name the file, and a failed write leaves nothing behind.
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <string>

#include "io/image_file.h"
#include "test_support.h"
#include "util/error.h"

namespace voxr {
namespace {

namespace fs = std::filesystem;

// A 7 x 5 gradient with distinct values per channel and a varying alpha.
ImageRgba gradient() {
  ImageRgba image(7, 5);
  for (uint32_t y = 0; y < image.height; ++y)
    for (uint32_t x = 0; x < image.width; ++x)
      image.at(x, y) = glm::vec4(x / 6.0f, y / 4.0f, (x + y) / 10.0f, 1.0f - x / 12.0f);
  return image;
}

std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "no error";
}

TEST(ImageFile, SrgbTransferMatchesTheStandard) {
  EXPECT_FLOAT_EQ(linear_to_srgb(0.0f), 0.0f);
  EXPECT_FLOAT_EQ(linear_to_srgb(1.0f), 1.0f);
  EXPECT_NEAR(linear_to_srgb(0.5f), 0.735357f, 1e-5f);   // the familiar 188/255
  EXPECT_NEAR(linear_to_srgb(0.002f), 0.02584f, 1e-5f);  // linear segment
  EXPECT_NEAR(linear_to_srgb(2.0f), 1.0f, 1e-6f);        // clamped
  for (float v = 0.0f; v <= 1.0f; v += 0.01f) EXPECT_NEAR(srgb_to_linear(linear_to_srgb(v)), v, 1e-5f);
}

TEST(ImageFile, ExrKeepsLinearFloatsExactly) {
  test::TempDir dir;
  ImageRgba image = gradient();
  image.at(3, 2) = glm::vec4(12.5f, 1e-6f, 0.0f, 1.0f);  // HDR and tiny values survive
  const fs::path path = dir.path() / "g.exr";
  write_image(image, path);
  const ImageRgba back = read_image(path);
  ASSERT_EQ(back.width, image.width);
  ASSERT_EQ(back.height, image.height);
  for (size_t i = 0; i < image.pixels.size(); ++i)
    EXPECT_EQ(back.pixels[i], image.pixels[i]) << "pixel " << i;
}

TEST(ImageFile, PngStoresSrgbAndDecodesWithinAStep) {
  test::TempDir dir;
  const ImageRgba image = gradient();
  const fs::path path = dir.path() / "g.PNG";  // extensions in any case
  write_image(image, path);
  const ImageRgba back = read_image(path);
  ASSERT_EQ(back.width, image.width);
  for (size_t i = 0; i < image.pixels.size(); ++i)
    for (int c = 0; c < 4; ++c) {
      // Half an 8-bit step in the encoding, mapped back through the transfer function's slope.
      const float v = image.pixels[i][c];
      const float step = c == 3 ? 0.5f / 255.0f + 1e-6f
                                : std::abs(srgb_to_linear(linear_to_srgb(v) + 0.5f / 255.0f) - v) + 1e-6f;
      EXPECT_NEAR(back.pixels[i][c], v, step) << "pixel " << i << " channel " << c;
    }
  // Linear 0.5 is stored as 188, not 128: the file is sRGB-encoded.
  ImageRgba grey(1, 1, glm::vec4(0.5f, 0.5f, 0.5f, 1.0f));
  write_image(grey, dir.path() / "grey.png");
  EXPECT_NEAR(linear_to_srgb(read_image(dir.path() / "grey.png").at(0, 0).x) * 255.0f, 188.0f, 0.5f);
}

TEST(ImageFile, AnotherReaderOpensWhatVoxrWrites) {
  test::TempDir dir;
  ImageRgba image = gradient();
  image.at(2, 1) = glm::vec4(7.25f, 0.0f, 1e-4f, 1.0f);
  for (const char* name : {"o.png", "o.exr"}) {
    const fs::path path = dir.path() / name;
    write_image(image, path);
    OIIO::ImageSpec config;
    config.attribute("oiio:UnassociatedAlpha", 1);  // colour as stored, not multiplied by alpha
    std::unique_ptr<OIIO::ImageInput> in = OIIO::ImageInput::open(path.string(), &config);
    ASSERT_TRUE(in) << name << ": " << OIIO::geterror();
    ASSERT_EQ(in->spec().width, int(image.width));
    ASSERT_EQ(in->spec().height, int(image.height));
    ASSERT_EQ(in->spec().nchannels, 4);
    const bool png = std::string(name) == "o.png";
    std::vector<float> values(image.pixels.size() * 4);
    ASSERT_TRUE(in->read_image(0, 0, 0, 4, OIIO::TypeDesc::FLOAT, values.data()));
    for (size_t i = 0; i < image.pixels.size(); ++i)
      for (int c = 0; c < 4; ++c) {
        const float v = image.pixels[i][c];
        const float expected = !png ? v : c == 3 ? v : linear_to_srgb(v);
        EXPECT_NEAR(values[4 * i + c], expected, png ? 0.5f / 255.0f + 1e-6f : 0.0f) << name << " " << i;
      }
  }
}

TEST(ImageFile, ReadsGreyAndRgbFilesOfAnotherWriter) {
  test::TempDir dir;
  const auto write = [&](const fs::path& path, int channels, OIIO::TypeDesc type, const void* data) {
    std::unique_ptr<OIIO::ImageOutput> out = OIIO::ImageOutput::create(path.string());
    ASSERT_TRUE(out);
    ASSERT_TRUE(out->open(path.string(), OIIO::ImageSpec(3, 2, channels, type)));
    ASSERT_TRUE(out->write_image(type, data));
    out->close();
  };
  const uint8_t grey[6] = {0, 51, 102, 153, 204, 255};
  write(dir.path() / "grey.png", 1, OIIO::TypeDesc::UINT8, grey);
  const ImageRgba g = read_image(dir.path() / "grey.png");
  ASSERT_EQ(g.width, 3u);
  for (int i = 0; i < 6; ++i) {
    const float v = srgb_to_linear(grey[i] / 255.0f);
    EXPECT_NEAR(g.pixels[i].x, v, 1e-6f);
    EXPECT_EQ(g.pixels[i].y, g.pixels[i].x);
    EXPECT_EQ(g.pixels[i].z, g.pixels[i].x);
    EXPECT_EQ(g.pixels[i].w, 1.0f);  // no alpha: opaque
  }
  const float rgb[18] = {0.5f, 2.0f, 0.0f, 1e-3f, 1, 1, 3, 3, 3, 0, 0, 0, 9, 8, 7, 0.25f, 0.125f, 64};
  for (const char* name : {"rgb.exr", "rgb.hdr"}) {
    write(dir.path() / name, 3, OIIO::TypeDesc::FLOAT, rgb);
    const ImageRgba f = read_image(dir.path() / name);
    ASSERT_EQ(f.height, 2u);
    const bool exact = std::string(name) == "rgb.exr";
    for (int i = 0; i < 6; ++i) {
      // RGBE: 8-bit mantissas under the pixel's largest component's exponent.
      const float step = std::max({rgb[3 * i], rgb[3 * i + 1], rgb[3 * i + 2]}) / 128.0f;
      for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(f.pixels[i][c], rgb[3 * i + c], exact ? 0.0f : step) << name << i << c;
      EXPECT_EQ(f.pixels[i].w, 1.0f);
    }
  }
}

TEST(ImageFile, ErrorsNameTheFileAndLeaveNothing) {
  test::TempDir dir;
  const ImageRgba image = gradient();
  EXPECT_NE(
      error_of([&] { write_image(image, dir.path() / "a.jpg"); }).find("a.jpg: unsupported image format"),
      std::string::npos);
  EXPECT_NE(
      error_of([&] { write_image(ImageRgba(), dir.path() / "b.png"); }).find("b.png: the image is empty"),
      std::string::npos);
  EXPECT_NE(error_of([&] { write_image(image, dir.path() / "missing" / "c.png"); }).find("c.png"),
            std::string::npos);
  EXPECT_NE(error_of([&] { read_image(dir.path() / "none.png"); }).find("none.png: no such file"),
            std::string::npos);
  for (const char* name : {"garbage.png", "garbage.exr", "garbage.hdr"}) {
    const fs::path garbage = dir.write(name, "not an image at all");
    EXPECT_NE(error_of([&] { read_image(garbage); }).find(std::string(name) + ": cannot read the image"),
              std::string::npos)
        << name;
  }
  EXPECT_NE(error_of([&] { read_image(dir.write("t.tga", "x")); }).find("t.tga: unsupported image format"),
            std::string::npos);
  size_t files = 0;
  for (const auto& e : fs::directory_iterator(dir.path()))
    files += e.path().stem() != "garbage" && e.path().filename() != "t.tga";
  EXPECT_EQ(files, 0u) << "a failed write left a file behind";
}

}  // namespace
}  // namespace voxr
