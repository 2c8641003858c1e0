// The transparent shadow methods `voxr render --shadows` offers, in one table.
#pragma once

#include <array>
#include <string_view>

namespace voxr {

enum class ShadowMethod { kVoxel, kUniform, kFilter, kOpaque, kReference, kNone };

struct ShadowMethodInfo {
  ShadowMethod method;
  const char* name;
  const char* summary;
};

inline constexpr std::array<ShadowMethodInfo, 6> kShadowMethods = {{
    {ShadowMethod::kVoxel, "voxel",
     "Chang & Lai: per-voxel optical depth from write count and material, prefix along the light"},
    {ShadowMethod::kUniform, "uniform",
     "Eisemann & Decoret: occupied voxels along the light ray x one absorption constant (slicemap)"},
    {ShadowMethod::kFilter, "filter",
     "game engines: opaque depth map x light-space product of every transparent surface's transmittance"},
    {ShadowMethod::kOpaque, "opaque", "classic depth shadow map: every caster blocks"},
    {ShadowMethod::kReference, "reference", "exact: Embree shadow rays through every surface (straight)"},
    {ShadowMethod::kNone, "none", "no shadows: every receiver fully lit"},
}};

const ShadowMethodInfo& shadow_method_info(ShadowMethod method);
// Throws voxr::Error naming the unknown method and listing the known ones.
ShadowMethod parse_shadow_method(std::string_view name);

}  // namespace voxr
