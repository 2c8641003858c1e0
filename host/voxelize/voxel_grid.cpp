#include "voxelize/voxel_grid.h"

#include <bit>

#include "core/error.h"

namespace voxr {

namespace {
constexpr Channel kAllChannels[] = {Channel::kOcc, Channel::kCount, Channel::kNormal, Channel::kMaterial,
                                    Channel::kInside};
}

const char* channel_name(Channel c) {
  switch (c) {
    case Channel::kOcc:
      return "occ";
    case Channel::kCount:
      return "count";
    case Channel::kNormal:
      return "normal";
    case Channel::kMaterial:
      return "material";
    case Channel::kInside:
      return "inside";
  }
  return "?";
}

ChannelSet ChannelSet::parse(std::string_view list) {
  ChannelSet set;
  while (!list.empty()) {
    const size_t comma = list.find(',');
    const std::string_view name = list.substr(0, comma);
    bool known = false;
    for (Channel c : kAllChannels)
      if (name == channel_name(c)) {
        set.add(c);
        known = true;
      }
    if (!known) fail("unknown channel '{}' (channels: occ, count, normal, material, inside)", name);
    list = comma == std::string_view::npos ? std::string_view() : list.substr(comma + 1);
  }
  return set;
}

std::string ChannelSet::to_string() const {
  std::string s;
  for (Channel c : kAllChannels)
    if (has(c)) s += (s.empty() ? "" : ",") + std::string(channel_name(c));
  return s;
}

void expand_bits(const std::vector<uint32_t>& bits, uint64_t begin, uint64_t end, uint8_t* out) {
  for (uint64_t l = begin; l < end; ++l) *out++ = uint8_t((bits[l >> 5] >> (l & 31)) & 1u);
}

VoxelGrid solid_occupancy(const VoxelGrid& grid) {
  VoxelGrid out;
  out.spec = grid.spec;
  out.occ = grid.occ;
  for (size_t w = 0; w < grid.inside.size(); ++w) out.occ[w] |= grid.inside[w];
  for (uint32_t w : out.occ) out.voxels_set += uint64_t(std::popcount(w));
  return out;
}

}  // namespace voxr
