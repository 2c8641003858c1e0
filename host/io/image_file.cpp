#include "io/image_file.h"

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfOutputFile.h>
#include <OpenEXR/ImfStdIO.h>
#include <png.h>
#include <stb_image.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <exception>
#include <memory>
#include <vector>

#include "io/atomic_file.h"
#include "util/error.h"
#include "util/file_extension.h"

// Each format through its own reference library: libpng (PNG), OpenEXR (EXR), stb_image (Radiance .hdr,
// read only). They replaced OpenImageIO, whose ~250 shared libraries cost a fresh `voxr render` process
// about 0.2 s to load before main (bench/results/render-fresh-process-*.md).

namespace voxr {

namespace fs = std::filesystem;

namespace {

// A library's message without line breaks (an error here is one line).
std::string one_line(std::string text) {
  std::replace(text.begin(), text.end(), '\n', ' ');
  while (!text.empty() && text.back() == ' ') text.pop_back();
  return text.empty() ? "unknown error" : text;
}

std::vector<char> encode_png(const ImageRgba& image, const std::string& name) {
  std::vector<uint8_t> encoded(image.pixels.size() * 4);
  for (size_t i = 0; i < image.pixels.size(); ++i) {
    const glm::vec4& p = image.pixels[i];
    for (int c = 0; c < 3; ++c) encoded[4 * i + c] = uint8_t(std::lround(255.0f * linear_to_srgb(p[c])));
    encoded[4 * i + 3] = uint8_t(std::lround(255.0f * std::clamp(p.w, 0.0f, 1.0f)));
  }
  png_image png{};
  png.version = PNG_IMAGE_VERSION;
  png.width = image.width;
  png.height = image.height;
  png.format = PNG_FORMAT_RGBA;  // sRGB-encoded, alpha not premultiplied
  // Fast zlib settings: a fresh `voxr render` spent ~40 ms of its 0.4 s in deflate at 512 x 512 with the
  // defaults (files ~1.3x larger). One pass into a worst-case-sized buffer: write_get_memory_size would
  // compress the image a second time to learn the size.
  png.flags = PNG_IMAGE_FLAG_FAST;
  png_alloc_size_t size = PNG_IMAGE_PNG_SIZE_MAX(png);
  std::vector<char> bytes(size);
  if (!png_image_write_to_memory(&png, bytes.data(), &size, 0, encoded.data(), 0, nullptr))
    fail("{}: cannot encode the image: {}", name, one_line(png.message));
  bytes.resize(size);
  return bytes;
}

std::vector<char> encode_exr(const ImageRgba& image) {
  Imf::Header header(int(image.width), int(image.height));
  const char* names[4] = {"R", "G", "B", "A"};
  for (const char* n : names) header.channels().insert(n, Imf::Channel(Imf::FLOAT));
  Imf::StdOSStream stream;
  {
    Imf::OutputFile file(stream, header);
    Imf::FrameBuffer frame;
    char* base = reinterpret_cast<char*>(const_cast<glm::vec4*>(image.pixels.data()));
    for (int c = 0; c < 4; ++c)
      frame.insert(names[c], Imf::Slice(Imf::FLOAT, base + c * sizeof(float), sizeof(glm::vec4),
                                        sizeof(glm::vec4) * image.width));
    file.setFrameBuffer(frame);
    file.writePixels(int(image.height));
  }  // the file's destructor writes the line offsets
  const std::string text = stream.str();
  return std::vector<char>(text.begin(), text.end());
}

ImageRgba decode_png(const std::string& name) {
  png_image png{};
  png.version = PNG_IMAGE_VERSION;
  if (!png_image_begin_read_from_file(&png, name.c_str()))
    fail("{}: cannot read the image: {}", name, one_line(png.message));
  png.format = PNG_FORMAT_RGBA;  // grey and palette images expanded, no alpha -> opaque, 16 bits -> 8
  std::vector<uint8_t> values(PNG_IMAGE_SIZE(png));
  if (!png_image_finish_read(&png, nullptr, values.data(), 0, nullptr))
    fail("{}: cannot read the image: {}", name, one_line(png.message));
  ImageRgba image(png.width, png.height);
  for (size_t i = 0; i < image.pixels.size(); ++i)
    for (int c = 0; c < 4; ++c) {
      const float v = values[4 * i + c] / 255.0f;
      image.pixels[i][c] = c < 3 ? srgb_to_linear(v) : v;
    }
  return image;
}

ImageRgba decode_exr(const std::string& name) {
  Imf::InputFile file(name.c_str());
  const Imath::Box2i window = file.header().dataWindow();
  const int64_t width = int64_t(window.max.x) - window.min.x + 1;
  const int64_t height = int64_t(window.max.y) - window.min.y + 1;
  if (width <= 0 || height <= 0 || width * height > (int64_t(1) << 28)) fail("{}: not a 2-D image", name);
  ImageRgba image(uint32_t(width), uint32_t(height), glm::vec4(0.0f, 0.0f, 0.0f, 1.0f));
  // Slices are addressed by the data window's coordinates: shift the base to its origin.
  char* base = reinterpret_cast<char*>(image.pixels.data()) -
               (int64_t(window.min.x) + int64_t(window.min.y) * width) * int64_t(sizeof(glm::vec4));
  const size_t x_stride = sizeof(glm::vec4), y_stride = sizeof(glm::vec4) * size_t(width);
  const Imf::ChannelList& channels = file.header().channels();
  const bool grey = !channels.findChannel("R") && channels.findChannel("Y");
  Imf::FrameBuffer frame;
  const char* names[4] = {grey ? "Y" : "R", "G", "B", "A"};
  for (int c = 0; c < (grey ? 1 : 3); ++c)
    frame.insert(names[c], Imf::Slice(Imf::FLOAT, base + c * sizeof(float), x_stride, y_stride, 1, 1, 0.0));
  frame.insert("A", Imf::Slice(Imf::FLOAT, base + 3 * sizeof(float), x_stride, y_stride, 1, 1, 1.0));
  file.setFrameBuffer(frame);
  file.readPixels(window.min.y, window.max.y);
  if (grey)
    for (glm::vec4& p : image.pixels) p.y = p.z = p.x;
  return image;
}

ImageRgba decode_hdr(const std::string& name) {
  int width = 0, height = 0, channels = 0;
  std::unique_ptr<float, void (*)(void*)> values(stbi_loadf(name.c_str(), &width, &height, &channels, 4),
                                                 stbi_image_free);
  if (!values) fail("{}: cannot read the image: {}", name, one_line(stbi_failure_reason()));
  ImageRgba image{uint32_t(width), uint32_t(height)};
  std::copy_n(values.get(), size_t(width) * height * 4, &image.pixels[0].x);
  return image;
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
  // Encoded in memory, then written through AtomicFile.
  std::vector<char> bytes;
  if (ext == ".png") {
    bytes = encode_png(image, name);
  } else {
    try {
      bytes = encode_exr(image);
    } catch (const std::exception& e) {
      fail("{}: cannot encode the image: {}", name, one_line(e.what()));
    }
  }
  AtomicFile file(path);
  file.write(bytes.data(), bytes.size());
  file.commit();
}

ImageRgba read_image(const fs::path& path) {
  const std::string name = path.string(), ext = lower_extension(path);
  std::error_code ec;
  if (!fs::exists(path, ec)) fail("{}: no such file", name);
  if (ext == ".png") return decode_png(name);
  if (ext == ".hdr") return decode_hdr(name);
  if (ext != ".exr") fail("{}: unsupported image format '{}' (readable: .png, .exr, .hdr)", name, ext);
  try {
    return decode_exr(name);
  } catch (const Error&) {
    throw;
  } catch (const std::exception& e) {
    fail("{}: cannot read the image: {}", name, one_line(e.what()));
  }
}

}  // namespace voxr
