#include "voxelize/device_colors.h"

#include <limits>

#include "util/error.h"

namespace voxr {

namespace {

uint32_t entries(size_t n, const char* what, const std::string& source) {
  if (n > std::numeric_limits<uint32_t>::max()) fail("{}: {} {} are more than 2^32-1", source, n, what);
  return uint32_t(n);
}

}  // namespace

ColorTables color_tables(const SoupColors& colors, const std::string& source) {
  ColorTables t;
  t.params.vertex_rgba = entries(colors.vertex_rgba.size(), "vertex colours", source);
  t.params.vertex_uv = entries(colors.vertex_uv.size(), "texture coordinates", source);
  t.params.triangle_look = entries(colors.triangle_look.size(), "triangle looks", source);
  t.params.looks = entries(colors.looks.size(), "looks", source);
  std::vector<uint64_t> offset;
  uint64_t total = 0;
  for (const SoupTexture& tex : colors.textures) {
    const std::string& name = tex.source.empty() ? source : tex.source;
    if (tex.width == 0 || tex.height == 0)
      fail("{}: the texture has no texels ({} x {})", name, tex.width, tex.height);
    if (tex.texels.size() != uint64_t(tex.width) * tex.height)
      fail("{}: the texture holds {} texels, not {} x {}", name, tex.texels.size(), tex.width, tex.height);
    offset.push_back(total);
    total += tex.texels.size();
  }
  if (total > std::numeric_limits<uint32_t>::max())
    fail("{}: the textures hold {} texels, more than the 2^32-1 the colour channel indexes", source, total);
  t.texels.reserve(total);
  for (const SoupTexture& tex : colors.textures)
    t.texels.insert(t.texels.end(), tex.texels.begin(), tex.texels.end());
  for (size_t l = 0; l < colors.looks.size(); ++l) {
    const SurfaceLook& look = colors.looks[l];
    VoxColorLook out{look.factor_rgba, 0, 0, 0};
    if (look.texture >= 0) {
      if (size_t(look.texture) >= colors.textures.size())
        fail("{}: look {} uses texture {} but there are only {} textures", source, l, look.texture,
             colors.textures.size());
      const SoupTexture& tex = colors.textures[size_t(look.texture)];
      out.texel_offset = uint32_t(offset[size_t(look.texture)]);
      out.width = tex.width;
      out.height = tex.height;
    }
    t.looks.push_back(out);
  }
  return t;
}

DeviceColors::DeviceColors(ClRuntime& cl, const TriangleSoup& soup, const std::string& source)
    : tables_(color_tables(soup.colors, source)) {
  const SoupColors& c = soup.colors;
  auto upload = [&](cl::Buffer& buffer, const void* data, uint64_t bytes, const char* what) {
    static const uint32_t placeholder = 0;
    if (bytes == 0) {
      data = &placeholder;
      bytes = sizeof(placeholder);
    }
    cl.host_buffer(buffer, data, bytes, what, "upload colors");
  };
  upload(vertex_rgba, c.vertex_rgba.data(), c.vertex_rgba.size() * 4, "vertex colours");
  upload(vertex_uv, c.vertex_uv.data(), c.vertex_uv.size() * sizeof(glm::vec2), "texture coordinates");
  upload(triangle_look, c.triangle_look.data(), c.triangle_look.size() * 4, "triangle looks");
  upload(looks, tables_.looks.data(), tables_.looks.size() * sizeof(VoxColorLook), "looks");
  upload(texels, tables_.texels.data(), tables_.texels.size() * 4, "texels");
}

}  // namespace voxr
