// Image files by extension, each through its format's own library: `.png` (libpng; 8-bit RGBA, colour
// sRGB-encoded from linear and clamped to [0, 1], alpha stored linearly), `.exr` (OpenEXR; linear 32-bit
// float RGBA, exact) and, for reading only, Radiance `.hdr` (stb_image; linear float). Written through
// AtomicFile (io/atomic_file.h): a file appears only once complete.
#pragma once

#include <filesystem>
#include <string>

#include "util/image_rgba.h"

namespace voxr {

// The extensions write_image and read_image accept, lower case with the dot, for messages and --help.
inline constexpr const char* kImageExtensions[] = {".png", ".exr"};

// True when `file`'s extension (any case) is one of kImageExtensions.
bool is_image_file(const std::filesystem::path& file);

// Writes `image` (linear RGBA) to `path`. Throws voxr::Error naming `path` for an unsupported extension, an
// empty image, a folder that does not exist or a failed write.
void write_image(const ImageRgba& image, const std::filesystem::path& path);

// Reads `path` (.png, .exr or .hdr, by extension) as linear RGBA: PNG decoded from sRGB (16-bit files at
// 8-bit precision; grey and palette images expanded), EXR's R, G, B (or Y) and A channels, images without
// alpha get alpha 1. Throws voxr::Error naming `path` when it is missing, has another extension or cannot be
// decoded: that includes a header claiming more pixels (or an EXR attribute more bytes) than the file can hold,
// refused before anything of that size is allocated, a .hdr that ends early or is not a Radiance file.
ImageRgba read_image(const std::filesystem::path& path);

// The sRGB transfer function (IEC 61966-2-1) and its inverse, per channel, for values in [0, 1].
float linear_to_srgb(float linear);
float srgb_to_linear(float encoded);

}  // namespace voxr
