#include "io/color_palette.h"

#include <algorithm>
#include <numeric>

#include "util/error.h"

namespace voxr {

namespace {

uint32_t component(uint32_t rgba, int c) {
  return (rgba >> (8 * c)) & 255u;
}

}  // namespace

uint32_t ColorPalette::entry_of(uint32_t rgba) const {
  const auto it = std::lower_bound(colors.begin(), colors.end(), rgba);
  VOXR_CHECK(it != colors.end() && *it == rgba);
  return index[size_t(it - colors.begin())];
}

ColorPalette median_cut_palette(std::span<const uint32_t> input, size_t max_entries) {
  VOXR_CHECK(max_entries >= 1);
  ColorPalette p;
  std::vector<uint32_t> sorted(input.begin(), input.end());
  std::sort(sorted.begin(), sorted.end());
  std::vector<uint64_t> weight;
  for (size_t i = 0; i < sorted.size(); ++i) {
    if (p.colors.empty() || p.colors.back() != sorted[i]) {
      p.colors.push_back(sorted[i]);
      weight.push_back(0);
    }
    ++weight.back();
  }
  const size_t n = p.colors.size();
  p.index.assign(n, 0);
  if (n <= max_entries) {
    p.entries = p.colors;
    std::iota(p.index.begin(), p.index.end(), 0u);
    return p;
  }
  // Boxes as ranges of `order`, a permutation of the distinct colours.
  std::vector<uint32_t> order(n);
  std::iota(order.begin(), order.end(), 0u);
  struct Box {
    size_t begin, end;
  };
  std::vector<Box> boxes = {{0, n}};
  auto extent = [&](const Box& b, int c) {
    uint32_t lo = 255, hi = 0;
    for (size_t i = b.begin; i < b.end; ++i) {
      lo = std::min(lo, component(p.colors[order[i]], c));
      hi = std::max(hi, component(p.colors[order[i]], c));
    }
    return hi - lo;
  };
  while (boxes.size() < max_entries) {
    size_t best = boxes.size();
    int best_c = 0;
    uint32_t best_extent = 0;
    for (size_t b = 0; b < boxes.size(); ++b) {
      if (boxes[b].end - boxes[b].begin < 2) continue;
      for (int c = 0; c < 4; ++c) {
        const uint32_t e = extent(boxes[b], c);
        if (e > best_extent) {
          best = b;
          best_c = c;
          best_extent = e;
        }
      }
    }
    if (best == boxes.size()) break;  // every box holds one colour
    Box& box = boxes[best];
    std::sort(order.begin() + ptrdiff_t(box.begin), order.begin() + ptrdiff_t(box.end),
              [&](uint32_t a, uint32_t b) {
                const uint32_t ca = component(p.colors[a], best_c), cb = component(p.colors[b], best_c);
                return ca != cb ? ca < cb : p.colors[a] < p.colors[b];
              });
    uint64_t total = 0;
    for (size_t i = box.begin; i < box.end; ++i) total += weight[order[i]];
    uint64_t lower = 0;
    size_t split = box.begin;
    while (split < box.end - 1 && 2 * lower < total) lower += weight[order[split++]];
    split = std::max(split, box.begin + 1);
    const Box upper{split, box.end};
    box.end = split;
    boxes.insert(boxes.begin() + ptrdiff_t(best) + 1, upper);
  }
  for (size_t b = 0; b < boxes.size(); ++b) {
    uint64_t sum[4] = {0, 0, 0, 0}, w = 0;
    for (size_t i = boxes[b].begin; i < boxes[b].end; ++i) {
      const uint32_t c = order[i];
      for (int q = 0; q < 4; ++q) sum[q] += weight[c] * component(p.colors[c], q);
      w += weight[c];
      p.index[c] = uint32_t(b);
    }
    uint32_t entry = 0;
    for (int q = 0; q < 4; ++q) entry |= uint32_t((sum[q] + w / 2) / w) << (8 * q);
    p.entries.push_back(entry);
  }
  return p;
}

}  // namespace voxr
