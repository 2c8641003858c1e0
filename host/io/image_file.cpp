#include "io/image_file.h"

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <memory>
#include <vector>

#include "core/error.h"
#include "core/file_extension.h"
#include "io/atomic_file.h"

namespace voxr {

namespace fs = std::filesystem;

namespace {

// OpenImageIO's message without line breaks (an error here is one line).
std::string one_line(std::string text) {
  std::replace(text.begin(), text.end(), '\n', ' ');
  while (!text.empty() && text.back() == ' ') text.pop_back();
  return text.empty() ? "unknown error" : text;
}

}  // namespace

bool is_image_file(const fs::path& file) {
  const std::string ext = lower_extension(file);
  return std::any_of(std::begin(kImageExtensions), std::end(kImageExtensions),
                     [&](const char* e) { return ext == e; });
}

float linear_to_srgb(float linear) {
  const float c = std::clamp(linear, 0.0f, 1.0f);
  return c <= 0.0031308f ? 12.92f * c : 1.055f * std::pow(c, 1.0f / 2.4f) - 0.055f;
}

float srgb_to_linear(float encoded) {
  const float c = std::clamp(encoded, 0.0f, 1.0f);
  return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
}

void write_image(const ImageRgba& image, const fs::path& path) {
  const std::string name = path.string(), ext = lower_extension(path);
  if (!is_image_file(path)) fail("{}: unsupported image format '{}' (supported: .png, .exr)", name, ext);
  if (image.width == 0 || image.height == 0 || image.pixels.size() != size_t(image.width) * image.height)
    fail("{}: the image is empty or its pixels do not match its size", name);
  check_output_path(path);

  // Encoded in memory (OpenImageIO's IOProxy), then written through AtomicFile.
  std::vector<unsigned char> bytes;
  OIIO::Filesystem::IOVecOutput memory(bytes);
  std::unique_ptr<OIIO::ImageOutput> out = OIIO::ImageOutput::create(name);
  if (!out) fail("{}: OpenImageIO cannot write {}: {}", name, ext, one_line(OIIO::geterror()));
  const bool png = ext == ".png";
  OIIO::ImageSpec spec(int(image.width), int(image.height), 4,
                       png ? OIIO::TypeDesc::UINT8 : OIIO::TypeDesc::FLOAT);
  void* proxy = &memory;
  spec.attribute("oiio:ioproxy", OIIO::TypeDesc::PTR, &proxy);
  if (png) spec.attribute("oiio:ColorSpace", "sRGB");
  // Colour is stored as given, not divided by alpha (OpenImageIO assumes premultiplied input otherwise).
  spec.attribute("oiio:UnassociatedAlpha", 1);
  if (!out->open(name, spec)) fail("{}: cannot encode the image: {}", name, one_line(out->geterror()));
  bool ok;
  if (png) {
    std::vector<uint8_t> encoded(image.pixels.size() * 4);
    for (size_t i = 0; i < image.pixels.size(); ++i) {
      const glm::vec4& p = image.pixels[i];
      for (int c = 0; c < 3; ++c) encoded[4 * i + c] = uint8_t(std::lround(255.0f * linear_to_srgb(p[c])));
      encoded[4 * i + 3] = uint8_t(std::lround(255.0f * std::clamp(p.w, 0.0f, 1.0f)));
    }
    ok = out->write_image(OIIO::TypeDesc::UINT8, encoded.data());
  } else {
    ok = out->write_image(OIIO::TypeDesc::FLOAT, image.pixels.data());
  }
  ok = out->close() && ok;
  if (!ok) fail("{}: cannot encode the image: {}", name, one_line(out->geterror()));
  AtomicFile file(path);
  file.write(bytes.data(), bytes.size());
  file.commit();
}

ImageRgba read_image(const fs::path& path) {
  const std::string name = path.string();
  std::error_code ec;
  if (!fs::exists(path, ec)) fail("{}: no such file", name);
  // Colour as stored, not multiplied by alpha on the way in.
  OIIO::ImageSpec config;
  config.attribute("oiio:UnassociatedAlpha", 1);
  std::unique_ptr<OIIO::ImageInput> in = OIIO::ImageInput::open(name, &config);
  if (!in) fail("{}: cannot read the image: {}", name, one_line(OIIO::geterror()));
  const OIIO::ImageSpec& spec = in->spec();
  if (spec.width <= 0 || spec.height <= 0 || spec.nchannels <= 0 || spec.depth > 1)
    fail("{}: not a 2-D image", name);
  ImageRgba image(uint32_t(spec.width), uint32_t(spec.height), glm::vec4(0.0f, 0.0f, 0.0f, 1.0f));
  std::vector<float> values(size_t(spec.width) * spec.height * spec.nchannels);
  if (!in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, values.data()))
    fail("{}: cannot read the image: {}", name, one_line(in->geterror()));
  const bool srgb = spec.format == OIIO::TypeDesc::UINT8 || spec.format == OIIO::TypeDesc::UINT16;
  const int channels = spec.nchannels;
  for (size_t i = 0; i < image.pixels.size(); ++i) {
    glm::vec4& p = image.pixels[i];
    const float* v = values.data() + i * size_t(channels);
    for (int c = 0; c < 3; ++c) {
      const float x = v[channels >= 3 ? c : 0];
      p[c] = srgb ? srgb_to_linear(x) : x;
    }
    if (channels == 4 || channels == 2) p.w = v[channels - 1];
  }
  return image;
}

}  // namespace voxr
