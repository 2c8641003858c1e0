// The refraction methods `voxr render --refraction` offers, their step rules and normal kinds, in tables.
#pragma once

#include <array>
#include <cstdint>
#include <string_view>

#include "util/named_values.h"

namespace voxr {

enum class RefractionMethod {
  kVoxelMulti,
  kVoxelTwo,
  kVoxelExact,
  kImageSpace,
  kDistanceMaps,
  kReference,
  kReferenceFull,
  kNone
};
// How a voxel march advances: the papers' fixed step (one voxel along the dominant axis, length h / cos
// theta) or the exact voxel traversal (3-D DDA, Amanatides & Woo 1987).
enum class StepRule { kPapers, kDda };
// Where a boundary voxel's normal comes from: the voxel's own normal-sum channel (the papers), or the
// normal sums of its 3x3x3 neighbourhood of the same material weighted by distance to the hit (smooth).
enum class NormalKind { kVoxel, kSmooth };
// Which grids the voxel methods march: a fine grid fitted to the dielectrics with a coarse one over the whole
// scene beyond it, or one grid over the whole scene (the papers).
enum class RefractionGrid { kFitted, kScene };
inline constexpr uint32_t kCoarseDivisor = 2;

using RefractionMethodInfo = NamedValue<RefractionMethod>;
inline constexpr std::array<RefractionMethodInfo, 8> kRefractionMethods = {{
    {RefractionMethod::kVoxelMulti, "voxel-multi",
     "Chang & Lai PG 2011: Snell-law marching through the voxels, refracting at every boundary"},
    {RefractionMethod::kVoxelTwo, "voxel-two",
     "Chang & Lai TR 1688: exact front surface, back surface found by marching, two refractions"},
    {RefractionMethod::kVoxelExact, "voxel-exact",
     "beyond the papers: the matched path on the exact triangles listed per voxel, rebuilt every frame"},
    {RefractionMethod::kImageSpace, "image-space",
     "Wyman 2005: front/back depth and normal buffers, d_V/d_N distance, nearby geometry by iteration"},
    {RefractionMethod::kDistanceMaps, "distance-maps",
     "GPU Gems 3 ch. 17: depth-peeled cube distance maps of the refractor, linear + secant search per ray"},
    {RefractionMethod::kReference, "reference",
     "exact, matched: Embree Whitted tracing of the refracted path with the voxel methods' model"},
    {RefractionMethod::kReferenceFull, "reference-full",
     "exact, full: Embree Whitted tracing of reflection and refraction at every interface, exact Fresnel, "
     "each branch until its weight falls below 1e-3"},
    {RefractionMethod::kNone, "none", "no refraction: dielectrics shaded flat"},
}};

using StepRuleInfo = NamedValue<StepRule>;
inline constexpr std::array<StepRuleInfo, 2> kStepRules = {{
    {StepRule::kPapers, "papers", "fixed step h / cos theta along the dominant axis (may skip corners)"},
    {StepRule::kDda, "dda", "exact voxel traversal (3-D DDA): every voxel the ray passes through"},
}};

using NormalKindInfo = NamedValue<NormalKind>;
inline constexpr std::array<NormalKindInfo, 2> kNormalKinds = {{
    {NormalKind::kVoxel, "voxel", "the voxel's normal sum (the papers)"},
    {NormalKind::kSmooth, "smooth", "normal sums of the 3x3x3 neighbours, weighted by distance to the hit"},
}};

using RefractionGridInfo = NamedValue<RefractionGrid>;
inline constexpr std::array<RefractionGridInfo, 2> kRefractionGrids = {{
    {RefractionGrid::kFitted, "fitted",
     "a fine grid over the dielectrics (2 voxels of margin), --res voxels along its longest side, and a "
     "coarse "
     "grid over the whole scene, --coarse-res (default --res/2) along its longest side, for what a ray meets "
     "beyond "
     "the fine grid"},
    {RefractionGrid::kScene, "scene",
     "one grid over the whole scene, --res voxels along its longest side (the papers)"},
}};

// `voxr render`'s refraction when none is asked for, chosen by the speed/accuracy chart: exact against the
// matched reference (68.8 dB on the built-in scene, where voxel-multi gives 32.5 dB; 47-102 dB on the
// twelve refraction scenes) and faster than voxel-multi on ten of them
// (bench/results/refraction-exact-pocl-2core.md; README "Choosing methods").
inline constexpr RefractionMethod kDefaultRefractionMethod = RefractionMethod::kVoxelExact;

const RefractionMethodInfo& refraction_method_info(RefractionMethod method);
const StepRuleInfo& step_rule_info(StepRule rule);
const NormalKindInfo& normal_kind_info(NormalKind kind);
const RefractionGridInfo& refraction_grid_info(RefractionGrid grid);
// Each throws voxr::Error naming the unknown value and listing the known ones.
RefractionMethod parse_refraction_method(std::string_view name);
StepRule parse_step_rule(std::string_view name);
NormalKind parse_normal_kind(std::string_view name);
RefractionGrid parse_refraction_grid(std::string_view name);

// Whether `method` marches the voxel grid / runs on the host with Embree.
inline bool is_voxel_refraction(RefractionMethod m) {
  return m == RefractionMethod::kVoxelMulti || m == RefractionMethod::kVoxelTwo;
}
inline bool is_reference_refraction(RefractionMethod m) {
  return m == RefractionMethod::kReference || m == RefractionMethod::kReferenceFull;
}

struct RefractionOptions {
  RefractionMethod method = RefractionMethod::kNone;
  // Voxel methods: voxels along the longest side of the fine grid (fitted: the dielectrics' bounds and a
  // margin; scene: the whole scene). voxel-exact: of the whole scene's grid of triangle lists, a speed knob
  // only.
  uint32_t resolution = 256;
  RefractionGrid grid = RefractionGrid::kFitted;
  // kFitted: voxels along the coarse grid's longest side (the whole scene); 0: resolution / kCoarseDivisor.
  // On thin-vase-floor at 256 (voxel-multi): coarse 64 gives image RMSE 0.0554, 128 0.0509, 256 0.0448.
  uint32_t coarse_resolution = 0;
  // The papers' step and smooth normals: the most accurate voxel-multi on average over the refraction scenes
  // and faster than the DDA (bench/results/refraction-pocl-2core.md: the DDA visits every voxel a ray clips
  // of a surface's conservative shell and refracts early or twice).
  StepRule step = StepRule::kPapers;
  NormalKind normals = NormalKind::kSmooth;
  // A boundary voxel within the run just refracted at is a new interface only when its normal turns more
  // than this from the last refraction normal (PG 2011's angle threshold), in degrees.
  float angle_threshold_deg = 60.0f;
  // distance-maps: refractor layers (depth-peeled cube maps), texels per cube face side, and the most
  // interfaces a path meets (render/distance_map_refraction.h).
  uint32_t layers = 4;
  uint32_t layer_res = 128;
  uint32_t max_events = 32;  // VOXR_PATH_MAX_EVENTS
};

}  // namespace voxr
