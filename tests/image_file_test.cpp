// PNG and EXR files (io/image_file.h): EXR keeps linear floats exactly, PNG stores sRGB-encoded 8-bit colour
// and decodes back within a quantization step, OpenImageIO (an independent reader and writer) agrees both
// ways, errors name the file, a failed write leaves nothing behind, and a header claiming more than its file
// holds is refused before its pixels are allocated.
#include <OpenImageIO/imageio.h>
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <sys/resource.h>
#include <zlib.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <functional>
#include <iterator>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "cli_support.h"
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

// A PNG of `width` x `height` 8-bit RGBA pixels, its IDAT `idat` (not necessarily enough for the pixels).
std::string png_file(uint32_t width, uint32_t height, const std::string& idat) {
  const auto chunk = [](const std::string& kind, const std::string& data) {
    std::string c;
    for (int i = 3; i >= 0; --i) c += char(uint32_t(data.size()) >> (8 * i));
    const std::string body = kind + data;
    const uint32_t crc = uint32_t(crc32(0, reinterpret_cast<const Bytef*>(body.data()), uInt(body.size())));
    c += body;
    for (int i = 3; i >= 0; --i) c += char(crc >> (8 * i));
    return c;
  };
  std::string ihdr;
  for (uint32_t v : {width, height})
    for (int i = 3; i >= 0; --i) ihdr += char(v >> (8 * i));
  ihdr += std::string("\x08\x06\x00\x00\x00", 5);  // 8 bits, RGBA, deflate, filter 0, no interlace
  return "\x89PNG\r\n\x1a\n" + chunk("IHDR", ihdr) + chunk("IDAT", idat) + chunk("IEND", "");
}

// Fuzzing the environment image path (fuzz/fuzz_env_image.cpp) found the first; the others came from reading
// the decoders while it ran. Each is refused with one line naming the file, before a buffer of the size its
// header claims is allocated.
TEST(ImageFile, RefusesHeadersThatClaimMoreThanTheFileHolds) {
  test::TempDir dir;
  const std::string radiance = "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n";
  const auto error_for = [&](const std::string& name, const std::string& content) {
    const fs::path file = dir.write(name, content);
    return std::pair(error_of([&] { read_image(file); }), file.string() + ": ");
  };
  // No width: stb_image returned a 0 x 2 image, and copying its pixels dereferenced an empty vector.
  auto [e, f] = error_for("no_width.hdr", radiance + "-Y 2 +X \n");
  EXPECT_EQ(e, f + "not a 2-D image");
  // 7 x 16 M pixels in 60 bytes: stb_image allocated 1.8 GB and decoded the missing bytes as zeros.
  std::tie(e, f) = error_for("tall.hdr", radiance + "-Y 16000000 +X 7\n" + std::string(8, '\0'));
  EXPECT_EQ(e, f + "cannot read the image: the file is too short for its 7x16000000 pixels");
  // 2 x 2 pixels, the last one's 4 bytes missing: read as black before.
  std::tie(e, f) = error_for("cut.hdr", radiance + "-Y 2 +X 2\n" + std::string(12, '\x80'));
  EXPECT_EQ(e, f + "cannot read the image: the file ends before its last pixel");
  // A run of length 0 in a run-length scanline: stb_image looped forever (fuzz_env_image).
  std::tie(e, f) =
      error_for("zero_run.hdr", radiance + "-Y 1 +X 8\n" + std::string("\x02\x02\x00\x08\x00", 5));
  EXPECT_EQ(e, f + "cannot read the image: a run of length 0 in scanline 0");
  // The file ending inside a run-length scanline: stb_image read a 0 run past the end, and looped.
  std::tie(e, f) =
      error_for("cut_run.hdr", radiance + "-Y 1 +X 8\n" + std::string("\x02\x02\x00\x08\x88\x64", 6));
  EXPECT_EQ(e, f + "cannot read the image: the file ends before its last pixel");
  // Another format named .hdr: stb_image decoded it as 8-bit gamma 2.2.
  std::tie(e, f) = error_for("png.hdr", png_file(1, 1, "x"));
  EXPECT_EQ(e, f + "cannot read the image: not a Radiance HDR file");
  // An attribute of a type OpenEXR does not know, its size 2^31 - 1: OpenEXR allocated it before finding the
  // file too short.
  write_image(gradient(), dir.path() / "big_attribute.exr");
  std::string exr;
  {
    std::ifstream in(dir.path() / "big_attribute.exr", std::ios::binary);
    exr.assign(std::istreambuf_iterator<char>(in), {});
  }
  const std::string attribute("screenWindowWidth\0float\0", 24);
  ASSERT_NE(exr.find(attribute), std::string::npos);
  const size_t size_at = exr.find(attribute) + attribute.size();
  exr[size_at - 8] = 'X';  // an attribute "screenWindowWidtX" of type "floaX"
  exr[size_at - 2] = 'X';
  exr.replace(size_at, 4, std::string("\xff\xff\xff\x7f", 4));
  std::tie(e, f) = error_for("big_attribute.exr", exr);
  EXPECT_EQ(e,
            f + fmt::format(
                    "cannot read the image: header attribute 'screenWindowWidtX' claims 2147483647 bytes, {} "
                    "are left in the file",
                    exr.size() - size_at - 4));
  // An EXR of 2 x 512 texels, its data window made 2^16 wide (512 MiB as RGBA floats) and its last chunks cut
  // off: the image was allocated before OpenEXR found the pixel data missing (fuzz_env_image); now the pixels
  // are decoded into one row first.
  write_image(ImageRgba(2, 512, glm::vec4(1.0f)), dir.path() / "wide.exr");
  {
    std::ifstream in(dir.path() / "wide.exr", std::ios::binary);
    exr.assign(std::istreambuf_iterator<char>(in), {});
  }
  const std::string window("dataWindow\0box2i\0\x10\0\0\0", 21);
  ASSERT_NE(exr.find(window), std::string::npos);
  const size_t x_max_at = exr.find(window) + window.size() + 8;
  exr.replace(x_max_at, 4, std::string("\xff\xff\x00\x00", 4));  // x max 2^16 - 1
  exr.resize(exr.size() - 100);                                  // the last chunks cut off
  rusage before{};
  getrusage(RUSAGE_SELF, &before);
  std::tie(e, f) = error_for("wide.exr", exr);
  EXPECT_EQ(e.rfind(f + "cannot read the image: ", 0), 0u) << e;
  EXPECT_EQ(e.find('\n'), std::string::npos) << e;
  rusage after{};
  getrusage(RUSAGE_SELF, &after);
  EXPECT_LT(after.ru_maxrss - before.ru_maxrss, 256 * 1024) << "KiB more at the peak";
  // 20000 x 20000 RGBA in 58 bytes: 1.6 GB allocated before libpng found the data missing.
  std::tie(e, f) = error_for("huge.png", png_file(20000, 20000, "x"));
  EXPECT_EQ(e, f + "cannot read the image: the file is too short for its 20000x20000 pixels");
}

// The bounds refuse nothing real: a wide constant Radiance image is the smallest file for its size (every
// scanline one 127-pixel run per channel and a shorter one), and a constant PNG compresses near deflate's
// limit.
TEST(ImageFile, ReadsMaximallyCompressedFilesOfAnotherWriter) {
  test::TempDir dir;
  const auto write = [&](const fs::path& path, uint32_t width, uint32_t height, OIIO::TypeDesc type,
                         const void* data) {
    std::unique_ptr<OIIO::ImageOutput> out = OIIO::ImageOutput::create(path.string());
    ASSERT_TRUE(out);
    ASSERT_TRUE(out->open(path.string(), OIIO::ImageSpec(int(width), int(height), 3, type)));
    ASSERT_TRUE(out->write_image(type, data));
    out->close();
  };
  const uint32_t w = 381, h = 3;  // 3 runs of 127 per channel
  const std::vector<float> rgb(size_t(w) * h * 3, 0.5f);
  write(dir.path() / "wide.hdr", w, h, OIIO::TypeDesc::FLOAT, rgb.data());
  // Run-length scanlines at the bound: 4 + 3 runs x 2 bytes x 4 channels each, plus a header.
  EXPECT_LE(fs::file_size(dir.path() / "wide.hdr"), h * (4 + 3 * 2 * 4) + 200u);
  const ImageRgba hdr = read_image(dir.path() / "wide.hdr");
  ASSERT_EQ(hdr.width, w);
  ASSERT_EQ(hdr.height, h);
  for (const glm::vec4& p : hdr.pixels) EXPECT_EQ(p, glm::vec4(0.5f, 0.5f, 0.5f, 1.0f));
  // A constant EXR is far smaller than its image: decoded twice (io/image_file.cpp), exact.
  const ImageRgba flat(1024, 512, glm::vec4(0.25f, 0.5f, 2.0f, 1.0f));
  write_image(flat, dir.path() / "flat.exr");
  ASSERT_LT(fs::file_size(dir.path() / "flat.exr") * 64, flat.pixels.size() * sizeof(glm::vec4));
  EXPECT_EQ(read_image(dir.path() / "flat.exr").pixels, flat.pixels);
  const uint32_t side = 2000;
  const std::vector<uint8_t> black(size_t(side) * side * 3, 0);
  write(dir.path() / "black.png", side, side, OIIO::TypeDesc::UINT8, black.data());
  const ImageRgba png = read_image(dir.path() / "black.png");
  ASSERT_EQ(png.width, side);
  EXPECT_EQ(png.pixels.back(), glm::vec4(0.0f, 0.0f, 0.0f, 1.0f));
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
// The environment-image fuzzer's seeds (fuzz/corpus/env_image: the first byte picks the extension, byte % 3
// of .png, .exr, .hdr, as fuzz/fuzz_env_image.cpp reads them; the rest is the file) are valid images of
// every format (else the fuzzer would start from errors): each reads, finite and non-negative.
TEST(ImageFile, FuzzSeedCorpusReads) {
  test::TempDir dir;
  const fs::path corpus = fs::path(VOXR_SOURCE_DIR) / "fuzz" / "corpus" / "env_image";
  const char* const extensions[] = {".png", ".exr", ".hdr"};
  size_t files = 0;
  for (const auto& e : fs::directory_iterator(corpus)) {
    SCOPED_TRACE(e.path().string());
    const std::string bytes = test::slurp(e.path());
    ASSERT_GE(bytes.size(), 2u);
    const fs::path file = dir.path() / (e.path().stem().string() + extensions[uint8_t(bytes[0]) % 3]);
    std::ofstream(file, std::ios::binary).write(bytes.data() + 1, std::streamsize(bytes.size() - 1));
    const ImageRgba image = read_image(file);
    EXPECT_GT(size_t(image.width) * image.height, 0u);
    for (const glm::vec4& p : image.pixels)
      ASSERT_TRUE(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z) && p.x >= 0.0f);
    ++files;
  }
  EXPECT_GE(files, 7u);
}

}  // namespace voxr
