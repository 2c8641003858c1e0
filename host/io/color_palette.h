// A palette of at most N colours for a set of RGBA8 colours (the .vox writer's 255 entries for the color
// channel): median cut (Heckbert 1982), deterministic.
//   - the distinct colours, each weighted by how many times it occurs; if there are at most N, they are the
//     palette as they are (ascending RGBA8 value, R in the low byte) and every colour maps to itself;
//   - otherwise one box holds them all, and while there are fewer than N boxes, the box with the widest
//     extent along one component (R, G, B, A; ties: the earlier box, then the earlier component) is split
//     along that component at its weighted median (colours sorted by that component, then by value; the
//     lower part takes colours until it holds at least half the weight, leaving at least one colour on each
//     side); a box of one colour is not split;
//   - each box's entry is the weighted mean of its colours per component, rounded half up.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

namespace voxr {

struct ColorPalette {
  std::vector<uint32_t> entries;  // RGBA8, R in the low byte; at most the requested size
  std::vector<uint32_t> colors;   // the distinct input colours, ascending
  std::vector<uint32_t> index;    // index[i]: the entry of colors[i]

  // The entry index of `rgba`, which must be one of the input colours.
  uint32_t entry_of(uint32_t rgba) const;
};

// The palette of `colors` with at most `max_entries` (>= 1) entries; empty for no colours.
ColorPalette median_cut_palette(std::span<const uint32_t> colors, size_t max_entries);

}  // namespace voxr
