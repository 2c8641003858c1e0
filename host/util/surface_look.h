// How a surface is coloured, shared by the mesh readers (mesh/polygon_mesh.h) and the soup
// (core/triangle_soup.h SoupColors): one definition below both folders.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace voxr {

// A base-colour texture: RGBA8 texels, row 0 at the top of the image (v = 1), texel (x, y) at
// texels[y * width + x] with R in the low byte, as stored in the file (sRGB-encoded for the usual formats).
struct SoupTexture {
  uint32_t width = 0, height = 0;
  std::vector<uint32_t> texels;
  std::string source;  // the file, for messages
};

// How a face's surface is coloured (glTF's base colour): factor x texture(uv) x vertex colour, each RGBA in
// [0, 1] (8-bit values / 255), the texture sampled with wrap-around (GL_REPEAT) and nearest texel.
struct SurfaceLook {
  uint32_t factor_rgba = 0xffffffffu;  // RGBA8, R in the low byte
  int32_t texture = -1;                // index into the mesh's or soup's textures, -1 for none
};

}  // namespace voxr
