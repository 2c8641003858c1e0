// Base-colour textures for the mesh readers (util/surface_look.h SoupTexture): PNG, JPEG, TGA, BMP (and the
// other formats stb_image knows: GIF's first frame, PSD, PNM) decoded by stb_image (Debian libstb), to 8-bit
// RGBA with row 0 at the top. Grey and RGB are expanded (alpha 255), 16-bit channels reduced to 8 bits.
// stb_image rather than OpenImageIO: OIIO costs every fresh `voxr` process ~0.2 s of dynamic loading.
#pragma once

#include <filesystem>
#include <string>
#include <string_view>

#include "mesh/polygon_mesh.h"

namespace voxr {

// Largest texture accepted, in texels (2^26: 64 M texels, 256 MiB of RGBA8).
inline constexpr uint64_t kMaxTextureTexels = uint64_t(1) << 26;

// Decodes `bytes` (an image file's contents); `name` names it in messages and becomes the texture's source.
// The header is read first (stbi_info): an image of more than kMaxTextureTexels texels, or of more texels
// than its bytes can encode (16384 per byte), is refused before any pixel is allocated.
// Throws voxr::Error, one line starting with `name`: empty bytes, an unknown or corrupt image, too large.
SoupTexture decode_texture(const std::string& name, std::string_view bytes);

// decode_texture of the file `file`. Throws voxr::Error naming `referrer` (the mesh or material file that
// names the texture, with its line when `line` > 0) and the texture when the file is missing or unreadable.
SoupTexture read_texture(const std::filesystem::path& file, const std::string& referrer, size_t line = 0);

}  // namespace voxr

namespace voxr {

// An 8-bit channel from a colour component in [0, 1]: round(v * 255).
inline uint32_t unit_to_byte(double v) {
  return uint32_t(v * 255.0 + 0.5);
}

// RGBA8 (R in the low byte) from 8-bit channels.
inline uint32_t pack_rgba(uint32_t r, uint32_t g, uint32_t b, uint32_t a = 255) {
  return r | g << 8 | b << 16 | a << 24;
}

inline constexpr uint32_t kWhiteRgba = 0xffffffffu;

}  // namespace voxr
