// The transparent shadow methods `voxr render --shadows` offers, in one table.
#pragma once

#include <array>
#include <string_view>

#include "util/named_values.h"

namespace voxr {

// Receivers move this many slabs (or depth-map texels) towards the light and this many columns off their
// surface before a lookup: the least that kept self-shadow acne off the glass and default scenes' grazing
// receivers while costing the tree and the foliage least (bench/results/shadows-*.md: bias 1 / offset 0
// leaves acne, 2 / 1 leaks light).
inline constexpr float kDefaultShadowBias = 1.5f;
inline constexpr float kDefaultNormalOffset = 0.25f;

enum class ShadowMethod { kVoxel, kUniform, kFilter, kOpaque, kVoxelExact, kReference, kNone };

using ShadowMethodInfo = NamedValue<ShadowMethod>;

inline constexpr std::array<ShadowMethodInfo, 7> kShadowMethods = {{
    {ShadowMethod::kVoxel, "voxel",
     "Chang & Lai: per-voxel optical depth from write count and material, prefix along the light"},
    {ShadowMethod::kUniform, "uniform",
     "Eisemann & Decoret: occupied voxels along the light ray x one absorption constant (slicemap)"},
    {ShadowMethod::kFilter, "filter",
     "game engines: opaque depth map x light-space product of every transparent surface's transmittance"},
    {ShadowMethod::kOpaque, "opaque", "classic depth shadow map: every caster blocks"},
    {ShadowMethod::kVoxelExact, "voxel-exact",
     "beyond the papers: the shadow ray through per-voxel triangle lists, every crossing exact (no map)"},
    {ShadowMethod::kReference, "reference", "exact: Embree shadow rays through every surface (straight)"},
    {ShadowMethod::kNone, "none", "no shadows: every receiver fully lit"},
}};

// `voxr render`'s shadows when none are asked for, chosen by the speed/accuracy chart and the frame times:
// Chang & Lai's voxel shadow map errs a little (transmittance RMSE 0.026 on the built-in scene) and is
// 1.8-4.6x faster than voxel-exact on foliage (640x480: shadow-tree 122 vs 213 ms, tree-1m 189 vs 862 ms;
// bench/results/frame-targets-pocl-2core.md runs 5 and 5a); voxel-exact is exact (README "Choosing methods").
inline constexpr ShadowMethod kDefaultShadowMethod = ShadowMethod::kVoxel;

const ShadowMethodInfo& shadow_method_info(ShadowMethod method);
// Throws voxr::Error naming the unknown method and listing the known ones.
ShadowMethod parse_shadow_method(std::string_view name);

}  // namespace voxr
