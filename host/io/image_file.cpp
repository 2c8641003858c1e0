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
#include <fstream>
#include <iterator>
#include <memory>
#include <string>
#include <string_view>
#include <utility>
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
  // Deflate expands at most 1032-fold, and a row holds at least a filter byte and 1 bit per pixel: a header
  // claiming more than the file can hold is refused before its buffer is allocated (20000 x 20000 in 58 bytes
  // allocated 1.6 GB).
  std::error_code ec;
  const uint64_t file_bytes = fs::file_size(name, ec);
  if (ec || uint64_t(png.height) * (1 + (uint64_t(png.width) + 7) / 8) > 1032 * file_bytes) {
    png_image_free(&png);
    fail("{}: cannot read the image: the file is too short for its {}x{} pixels", name, png.width,
         png.height);
  }
  png.format = PNG_FORMAT_RGBA;  // grey and palette images expanded, no alpha -> opaque, 16 bits -> 8
  std::vector<uint8_t> values(size_t(png.width) * png.height * 4);
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

// OpenEXR allocates the declared size of a header attribute it reads as bytes (strings, unknown types) and a
// preview image's declared pixels before reading them (fuzz_env_image found 0.8-1.9 GB in 200-byte files):
// the headers are walked as OpenEXR reads them, and such an attribute larger than the rest of the file is
// refused first. Layout: magic, version (bit 12: multi-part, each header ends in a 0 byte, the list in
// another), then per attribute a name, a type name (0-terminated), a 4-byte little-endian size and the value:
// a channel list up to an empty name, fixed-size types by their layout, everything else by the size.
void check_exr_attribute_sizes(const std::string& name) {
  static const std::pair<std::string_view, int> kFixed[] = {{"box2i", 16},
                                                            {"box2f", 16},
                                                            {"v2i", 8},
                                                            {"v2f", 8},
                                                            {"v2d", 16},
                                                            {"v3i", 12},
                                                            {"v3f", 12},
                                                            {"v3d", 24},
                                                            {"float", 4},
                                                            {"double", 8},
                                                            {"int", 4},
                                                            {"compression", 1},
                                                            {"lineOrder", 1},
                                                            {"envmap", 1},
                                                            {"deepImageState", 1},
                                                            {"chromaticities", 32},
                                                            {"keycode", 28},
                                                            {"timecode", 8},
                                                            {"rational", 8},
                                                            {"m33f", 36},
                                                            {"m44f", 64},
                                                            {"m33d", 72},
                                                            {"m44d", 128},
                                                            {"tiledesc", 9}};
  std::ifstream in(name, std::ios::binary);
  std::error_code ec;
  const uint64_t file_bytes = fs::file_size(name, ec);
  char start[8];
  if (ec || !in.read(start, 8)) return;  // OpenEXR says what is wrong
  const bool multi_part = uint8_t(start[5]) & 0x10;
  const auto u32 = [&](uint32_t& v) {
    char b[4];
    if (!in.read(b, 4)) return false;
    v = 0;
    for (int i = 3; i >= 0; --i) v = v << 8 | uint8_t(b[i]);
    return true;
  };
  const auto refuse_beyond_end = [&](const std::string& attribute, uint64_t bytes) {
    const uint64_t left = file_bytes - uint64_t(in.tellg());
    if (bytes > left)
      fail("{}: cannot read the image: header attribute '{}' claims {} bytes, {} are left in the file", name,
           one_line(attribute), bytes, left);
  };
  std::string attribute, type, channel;
  while (in) {
    if (in.peek() == 0) {  // the end of a header
      in.get();
      if (!multi_part || in.peek() == 0 || in.peek() == EOF) return;
      continue;
    }
    uint32_t size = 0;
    if (!std::getline(in, attribute, '\0') || !std::getline(in, type, '\0') || !u32(size)) return;
    const auto fixed =
        std::find_if(std::begin(kFixed), std::end(kFixed), [&](const auto& f) { return f.first == type; });
    if (type == "chlist") {
      while (std::getline(in, channel, '\0') && !channel.empty()) in.seekg(16, std::ios::cur);
    } else if (fixed != std::end(kFixed)) {
      in.seekg(fixed->second, std::ios::cur);
    } else if (type == "preview") {
      uint32_t width = 0, height = 0;
      if (!u32(width) || !u32(height)) return;
      refuse_beyond_end(attribute, uint64_t(width) * height * 4);
      in.seekg(std::streamoff(uint64_t(width) * height * 4), std::ios::cur);
    } else {
      refuse_beyond_end(attribute, size);
      in.seekg(size, std::ios::cur);
    }
  }
}

ImageRgba decode_exr(const std::string& name) {
  check_exr_attribute_sizes(name);
  Imf::InputFile file(name.c_str());
  const Imath::Box2i window = file.header().dataWindow();
  const int64_t width = int64_t(window.max.x) - window.min.x + 1;
  const int64_t height = int64_t(window.max.y) - window.min.y + 1;
  if (width <= 0 || height <= 0 || width * height > (int64_t(1) << 28)) fail("{}: not a 2-D image", name);
  const Imf::ChannelList& channels = file.header().channels();
  const bool grey = !channels.findChannel("R") && channels.findChannel("Y");
  const auto read = [&](char* base, size_t x_stride, size_t y_stride) {
    Imf::FrameBuffer frame;
    const char* names[4] = {grey ? "Y" : "R", "G", "B", "A"};
    for (int c = 0; c < (grey ? 1 : 3); ++c)
      frame.insert(names[c], Imf::Slice(Imf::FLOAT, base + c * sizeof(float), x_stride, y_stride, 1, 1, 0.0));
    frame.insert("A", Imf::Slice(Imf::FLOAT, base + 3 * sizeof(float), x_stride, y_stride, 1, 1, 1.0));
    file.setFrameBuffer(frame);
    file.readPixels(window.min.y, window.max.y);
  };
  // A header can claim far more pixels than the file holds (fuzz_env_image found 7.6 M x 20, 2.4 GB as RGBA
  // floats, in 255 bytes). When the image would be over 64 times the file, its pixels are first decoded into
  // one row (y stride 0), so missing data is found before the image is allocated; real files are a few times
  // smaller than their image, and those much smaller decode fast. The row itself is 16 bytes a texel: a file
  // of one row of 117 M half texels still costs 1.9 GB here (OpenEXR accepts rows up to 2 GiB of file data).
  std::error_code ec;
  if (uint64_t(width * height) * sizeof(glm::vec4) > 64 * fs::file_size(name, ec)) {
    std::vector<glm::vec4> row(static_cast<size_t>(width));
    read(reinterpret_cast<char*>(row.data()) - int64_t(window.min.x) * int64_t(sizeof(glm::vec4)),
         sizeof(glm::vec4), 0);
  }
  ImageRgba image(uint32_t(width), uint32_t(height), glm::vec4(0.0f, 0.0f, 0.0f, 1.0f));
  // Slices are addressed by the data window's coordinates: shift the base to its origin.
  read(reinterpret_cast<char*>(image.pixels.data()) -
           (int64_t(window.min.x) + int64_t(window.min.y) * width) * int64_t(sizeof(glm::vec4)),
       sizeof(glm::vec4), sizeof(glm::vec4) * size_t(width));
  if (grey)
    for (glm::vec4& p : image.pixels) p.y = p.z = p.x;
  return image;
}

// A Radiance file in memory for stb_image's callbacks; `past_end` records a read at the end of the file
// (stb_image decodes the bytes a truncated file lacks as zeros).
struct HdrSource {
  std::vector<char> bytes;
  size_t pos = 0;
  bool past_end = false;

  static int read(void* user, char* data, int size) {
    HdrSource& s = *static_cast<HdrSource*>(user);
    const size_t n = std::min(size_t(std::max(size, 0)), s.bytes.size() - s.pos);
    if (n == 0 && size > 0) s.past_end = true;
    std::copy_n(s.bytes.data() + s.pos, n, data);
    s.pos += n;
    return int(n);
  }
  static void skip(void* user, int n) {
    HdrSource& s = *static_cast<HdrSource*>(user);
    s.pos = size_t(std::clamp<int64_t>(int64_t(s.pos) + n, 0, int64_t(s.bytes.size())));
  }
  static int eof(void* user) {
    const HdrSource& s = *static_cast<const HdrSource*>(user);
    return s.pos >= s.bytes.size();
  }
};

ImageRgba decode_hdr(const std::string& name) {
  HdrSource source;
  {
    std::ifstream in(name, std::ios::binary);
    source.bytes.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
    if (in.bad()) fail("{}: cannot read the image: read error", name);
  }
  const stbi_io_callbacks io{&HdrSource::read, &HdrSource::skip, &HdrSource::eof};
  // stbi_loadf would decode any format stb_image knows (JPEG, BMP, ...) and convert it from gamma 2.2.
  if (!stbi_is_hdr_from_callbacks(&io, &source))
    fail("{}: cannot read the image: not a Radiance HDR file", name);
  // A scanline takes 4 bytes a pixel, or for widths 8 to 32767 at least its 4-byte run-length header and one
  // 2-byte run of up to 127 pixels per channel: a header claiming more than the file holds is refused before
  // stb_image allocates its pixels (60 bytes claiming 7 x 16 M allocated 1.8 GB).
  int width = 0, height = 0, channels = 0;
  source.pos = 0;
  if (!stbi_info_from_callbacks(&io, &source, &width, &height, &channels))
    fail("{}: cannot read the image: {}", name, one_line(stbi_failure_reason()));
  // stb_image accepts a header without a width or height ("+X " followed by no number) as a 0-pixel image.
  if (width <= 0 || height <= 0) fail("{}: not a 2-D image", name);
  const uint64_t line_bytes =
      width >= 8 && width < 32768 ? 4 + 8 * ((uint64_t(width) + 126) / 127) : 4 * uint64_t(width);
  if (line_bytes * uint64_t(height) > source.bytes.size())
    fail("{}: cannot read the image: the file is too short for its {}x{} pixels", name, width, height);
  // stb_image's run-length decoder loops forever on a run of length 0 (fuzz_env_image: a 70-byte file): the
  // scanlines are walked first as it decodes them (4 header bytes 2 2 width, then per channel runs: a count
  // over 128 repeats the next byte count - 128 times, else count bytes follow), and a 0 run or a scanline the
  // file ends in is refused.
  const size_t header_end = std::string_view(source.bytes.data(), source.bytes.size()).find("\n\n");
  size_t pos = std::string_view(source.bytes.data(), source.bytes.size()).find('\n', header_end + 2) + 1;
  const auto byte = [&](size_t i) { return uint8_t(source.bytes[i]); };
  for (int y = 0; width >= 8 && width < 32768 && y < height && pos + 4 <= source.bytes.size(); ++y) {
    if (byte(pos) != 2 || byte(pos + 1) != 2 || (byte(pos + 2) & 0x80)) break;  // stb_image reads it flat
    pos += 4;
    for (int c = 0; c < 4; ++c)
      for (int x = 0; x < width;) {
        // stb_image would read a 0 run past the end
        if (pos >= source.bytes.size())
          fail("{}: cannot read the image: the file ends before its last pixel", name);
        const int count = byte(pos++);
        if (count == 0) fail("{}: cannot read the image: a run of length 0 in scanline {}", name, y);
        x += count > 128 ? count - 128 : count;
        pos += count > 128 ? 1 : size_t(count);
      }
  }
  source.pos = 0;
  source.past_end = false;
  std::unique_ptr<float, void (*)(void*)> values(
      stbi_loadf_from_callbacks(&io, &source, &width, &height, &channels, 4), stbi_image_free);
  if (!values) fail("{}: cannot read the image: {}", name, one_line(stbi_failure_reason()));
  if (source.past_end) fail("{}: cannot read the image: the file ends before its last pixel", name);
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
