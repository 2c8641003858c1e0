// The `color` channel's inputs on the device (kernels/common/vox_color.h samples them): a soup's vertex
// colours, texture coordinates and per-triangle looks as they are (in place on a CPU device), and the
// looks with every texture packed into one texel atlas. Uploaded once per mesh, only when colour is asked
// for (Voxelizer::run attaches it to the DeviceMesh); a mesh without it voxelizes white.
#pragma once

#include <cstdint>
#include <vector>

#include "cl/cl_runtime.h"
#include "core/triangle_soup.h"
#include "voxr_layout.h"

namespace voxr {

// The host side of the inputs: the entry counts of the soup's colour arrays (VoxColorParams: arrays
// shorter than the soup, e.g. after TriangleSoup::append of a colourless soup, leave the rest white), one
// VoxColorLook per look, and the atlas (the textures' texels one after another, in SoupColors::textures
// order). The CPU reference samples these same tables.
struct ColorTables {
  VoxColorParams params{};
  std::vector<VoxColorLook> looks;
  std::vector<uint32_t> texels;
};

// Throws voxr::Error naming `source` (the mesh) and the texture's own source for a texture whose texel count
// is not width x height or is empty, a look whose texture index is out of range, or an atlas beyond 2^32
// texels.
ColorTables color_tables(const SoupColors& colors, const std::string& source);

class DeviceColors {
 public:
  // Uploads `soup`'s colours (validated by color_tables). On a CPU device the per-vertex and per-triangle
  // arrays are read in place: the soup must outlive this object unchanged.
  DeviceColors(ClRuntime& cl, const TriangleSoup& soup, const std::string& source);

  const ColorTables& tables() const { return tables_; }
  // Buffers (a 4-byte placeholder for an absent array).
  cl::Buffer vertex_rgba, vertex_uv, triangle_look, looks, texels;

 private:
  ColorTables tables_;
};

}  // namespace voxr
