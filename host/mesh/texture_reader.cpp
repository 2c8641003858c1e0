#include "mesh/texture_reader.h"

#include <stb_image.h>

#include <cstring>
#include <memory>
#include <system_error>

#include "mesh/file_bytes.h"
#include "util/error.h"

namespace voxr {

namespace {

struct StbiFree {
  void operator()(stbi_uc* p) const { stbi_image_free(p); }
};

}  // namespace

SoupTexture decode_texture(const std::string& name, std::string_view bytes) {
  if (bytes.empty()) fail("{}: the texture file is empty", name);
  if (bytes.size() > size_t(1) << 31) fail("{}: the texture file is larger than 2 GiB", name);
  const auto* data = reinterpret_cast<const stbi_uc*>(bytes.data());
  const int size = int(bytes.size());
  int width = 0, height = 0, channels = 0;
  if (!stbi_info_from_memory(data, size, &width, &height, &channels))
    fail("{}: not a texture image voxr reads (PNG, JPEG, TGA, BMP): {}", name, stbi_failure_reason());
  if (width <= 0 || height <= 0) fail("{}: the texture has no pixels ({}x{})", name, width, height);
  const uint64_t texels = uint64_t(width) * uint64_t(height);
  if (texels > kMaxTextureTexels)
    fail("{}: the texture's {}x{} texels are more than voxr reads ({})", name, width, height,
         kMaxTextureTexels);
  // No format voxr reads packs more than 8 texels a byte before compression, and deflate at most ~1032
  // bytes into one: a header claiming more than that lies (the bound keeps a tiny file from allocating).
  if (texels > 16384 * uint64_t(bytes.size()))
    fail("{}: the texture header claims {}x{} texels but the file has only {} bytes", name, width, height,
         bytes.size());
  int w = 0, h = 0, n = 0;
  const std::unique_ptr<stbi_uc, StbiFree> pixels(stbi_load_from_memory(data, size, &w, &h, &n, 4));
  if (!pixels) fail("{}: cannot decode the texture: {}", name, stbi_failure_reason());
  if (w != width || h != height)
    fail("{}: the texture decodes to {}x{} texels but its header says {}x{}", name, w, h, width, height);
  SoupTexture t;
  t.width = uint32_t(w);
  t.height = uint32_t(h);
  t.texels.resize(texels);
  std::memcpy(t.texels.data(), pixels.get(), texels * 4);  // bytes R, G, B, A: R in the low byte
  t.source = name;
  return t;
}

SoupTexture read_texture(const std::filesystem::path& file, const std::string& referrer, size_t line) {
  const std::string where = line > 0 ? fmt::format("{}: line {}", referrer, line) : referrer;
  std::error_code ec;
  if (!std::filesystem::is_regular_file(file, ec))
    fail("{}: texture '{}' is not a readable file", where, file.string());
  try {
    const FileBytes bytes(file);
    return decode_texture(file.string(), bytes.view());
  } catch (const Error& e) {
    fail("{}: texture {}", where, e.what());
  }
}

}  // namespace voxr
