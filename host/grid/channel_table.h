// The one definition of every voxel channel: its name (as --channels spells it), the array name in .vti and
// .nrrd files (what voxr-view lists), the bit in a ChannelSet and in the kernels' channel masks, the
// element type and component count of the values a file holds, where it lives on the device (dense bits,
// or sparse: one entry per set voxel, indexed by the voxel's rank among the set voxels) and its unit.
// Host enum, kernel defines (channel_defines), writer array names and the viewer all read this table.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <string_view>

#include "cl/defines.h"

namespace voxr {

enum class Channel : uint32_t {
  kOcc = 1u << 0,
  kCount = 1u << 1,
  kNormal = 1u << 2,
  kMaterial = 1u << 3,
  kInside = 1u << 4,
  kColor = 1u << 5,
};

enum class ChannelLayout {
  kDenseBits,  // one bit per voxel, 32-bit words, linear index order (x fastest)
  kSparse,     // one entry per set (occupied) voxel, in rank order
};

enum class ElementType { kUInt8, kUInt32, kFloat32 };

struct ChannelInfo {
  Channel channel;
  const char* name;        // --channels, NRRD sibling suffix (out.<name>.nrrd)
  const char* array_name;  // .vti / .nrrd array name, voxr-view's list
  const char* define;      // kernel define holding the bit (VOX_CH_*)
  ElementType type;        // the values written to files
  uint32_t components;
  ChannelLayout layout;
  const char* unit;  // what one value means
};

inline constexpr std::array<ChannelInfo, 6> kChannelTable = {{
    {Channel::kOcc, "occ", "occupancy", "VOX_CH_OCC", ElementType::kUInt8, 1, ChannelLayout::kDenseBits,
     "1 where the voxel meets the surface"},
    {Channel::kCount, "count", "count", "VOX_CH_COUNT", ElementType::kUInt32, 1, ChannelLayout::kSparse,
     "triangles that wrote the voxel (the papers' degree of occlusion)"},
    {Channel::kNormal, "normal", "normal", "VOX_CH_NORMAL", ElementType::kFloat32, 3, ChannelLayout::kSparse,
     "unit vector in the grid's frame (GridSpec::axes; the world's for axis-aligned grids): the normalized "
     "sum "
     "of the writers' unit normals"},
    {Channel::kMaterial, "material", "material", "VOX_CH_MATERIAL", ElementType::kUInt32, 1,
     ChannelLayout::kSparse, "largest material id among the writers"},
    {Channel::kInside, "inside", "inside", "VOX_CH_INSIDE", ElementType::kUInt8, 1, ChannelLayout::kDenseBits,
     "1 where the voxel centre is inside the solid"},
    {Channel::kColor, "color", "color", "VOX_CH_COLOR", ElementType::kUInt8, 4, ChannelLayout::kSparse,
     "RGBA8 (R first): the mean over the (triangle, voxel) pairs of the triangle's base colour (factor x "
     "texture x vertex colour) at its point closest to the voxel centre, averaged as stored (sRGB-encoded, "
     "not linearised); white for a mesh without colours"},
}};

// The table entry of `c`.
const ChannelInfo& channel_info(Channel c);
inline const char* channel_name(Channel c) {
  return channel_info(c).name;
}
// The channel whose array_name is `array_name`, or nullptr.
const ChannelInfo* find_channel_array(std::string_view array_name);

// The kernel defines of the channel bits (VOX_CH_OCC=1, VOX_CH_COUNT=2, ...).
Defines channel_defines();

// A set of channels; occ is always present.
struct ChannelSet {
  uint32_t bits = uint32_t(Channel::kOcc);
  bool has(Channel c) const { return (bits & uint32_t(c)) != 0; }
  void add(Channel c) { bits |= uint32_t(c); }
  void remove(Channel c) {
    if (c != Channel::kOcc) bits &= ~uint32_t(c);
  }
  // Whether a sparse channel (count, normal, material, color) is in the set.
  bool sparse() const;
  // "occ,count,normal,material,inside,color" (any subset, any order; occ is always added). Throws voxr::Error
  // naming an unknown channel and listing the known ones.
  static ChannelSet parse(std::string_view list);
  std::string to_string() const;  // table order
  bool operator==(const ChannelSet&) const = default;
};

}  // namespace voxr
