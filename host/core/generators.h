// Procedural meshes. Every generator is deterministic (same arguments, same soup, bit for bit), closed
// surfaces share vertex indices (watertight: every undirected edge is used by exactly two triangles) and
// every triangle winds counter-clockwise seen from outside, so normals (b-a)x(c-a) point outwards and the
// signed volume is positive. Material ids are 0 except where a generator says otherwise.
#pragma once

#include <nlohmann/json_fwd.hpp>

#include <glm/glm.hpp>

#include <cstdint>
#include <string>
#include <vector>

#include "core/triangle_soup.h"

namespace voxr {

// Ring torus around the Y axis (the hole runs along Y), centred at the origin: `rings` segments around the
// major circle times `sides` around the tube, 2*rings*sides triangles (800 by default, the papers' torus).
// Needs major > minor > 0, rings >= 3, sides >= 3.
TriangleSoup make_torus(float major = 1.0f, float minor = 0.4f, int rings = 20, int sides = 20);

// Sphere at the origin with poles on the Y axis, each pole a single vertex: 2*slices*(stacks-1) triangles.
// Needs radius > 0, stacks >= 2, slices >= 3.
TriangleSoup make_uv_sphere(float radius = 1.0f, int stacks = 16, int slices = 32);

// Axis-aligned box, 8 vertices and 12 triangles. Needs lo < hi on every axis.
TriangleSoup make_box(glm::vec3 lo = glm::vec3(-0.5f), glm::vec3 hi = glm::vec3(0.5f));

// A vase standing on y = 0 around the Y axis, a closed solid with walls: outer surface, a flat rim at the
// top joining it to the inner surface, the inner surface offset inwards by `thickness`, and a bottom
// `thickness` thick. `profile` holds outer radii at evenly spaced heights from the bottom (first) to the top
// (last); the outline between them is a Catmull-Rom curve clamped between neighbouring radii, sampled at
// `rows` heights. Needs height > 2*thickness, thickness > 0, at least 2 profile radii all > thickness,
// segments >= 3, rows >= 1, fill in [0, 1].
// `fill` > 0 adds the liquid it holds (material 1; the vase is material 0): a closed solid filling the inside
// from the inner floor up to the inner surface's row nearest to fill x the inner height (at least the first),
// topped by a flat disc. Its floor and side are the vase's inner vertices bit for bit (the same outline
// points), so the two dielectrics share those faces exactly (a glass of water).
struct VaseParams {
  float height = 1.0f;
  std::vector<float> profile{0.30f, 0.42f, 0.45f, 0.36f, 0.22f, 0.20f, 0.26f};
  float thickness = 0.03f;
  int segments = 48;  // around the axis
  int rows = 32;      // along the height, per surface
  float fill = 0.0f;  // fraction of the inner height the liquid fills; 0: no liquid
};
TriangleSoup make_vase(const VaseParams& params = {});

// A small tree: a closed, tapered trunk (material 0) from y = 0 to y = 1, and leaves (material 1) in an
// ellipsoidal crown around (0, 1.25, 0). Each leaf is an open quad sheet (2 triangles, 4 vertices of its
// own) of random position, orientation and size; there are round(kTreeLeavesPerDensity * density) of them.
// Leaves are 0.08..0.13 x leaf_scale long and half that wide: a dense crown of small leaves (the shadow
// scenes: density 108, leaf_scale 0.2) lets light through as a real one does. Same parameters, same tree.
// Needs density >= 0 and leaf_scale > 0.
inline constexpr uint32_t kTreeTrunkMaterial = 0;
inline constexpr uint32_t kTreeLeafMaterial = 1;
inline constexpr float kTreeLeavesPerDensity = 300.0f;
TriangleSoup make_tree(float density = 1.0f, uint32_t seed = 1, float leaf_scale = 1.0f);

// A block of foliage for shadows among casters: `leaves` sheet leaves (material kFoliageLeafMaterial), each
// an open quad like the tree's (2 triangles, 4 vertices of its own) with a random normal and spin, a length
// in [0.75, 1.25) * leaf_size and half that width, centred uniformly in the box of extent `size` centred at
// the origin, inset by a leaf's largest half-diagonal (kFoliageLeafReach * leaf_size) so every vertex lies
// inside the box. 2 * leaves triangles. Same parameters, same block. Needs leaf_size > 0 and every side of
// `size` longer than 2 * kFoliageLeafReach * leaf_size.
inline constexpr uint32_t kFoliageLeafMaterial = 0;
inline constexpr float kFoliageLeafReach = 0.69877124f;  // half the diagonal of a 1.25 x 0.625 leaf
struct FoliageParams {
  glm::vec3 size{2.0f, 1.0f, 2.0f};
  uint32_t leaves = 2000;
  float leaf_size = 0.1f;  // mean leaf length, world units
  uint32_t seed = 1;
};
TriangleSoup make_foliage(const FoliageParams& params = {});

// Open square grid in the XZ plane at y = 0, centred at the origin, `size` = (extent along x, along z),
// subdivisions x subdivisions cells, 2 triangles each, normals +Y. Needs size > 0, subdivisions >= 1.
TriangleSoup make_plane(glm::vec2 size = glm::vec2(2.0f), int subdivisions = 1);

// Names make_generated knows, in the order error messages list them.
const std::vector<std::string>& generator_names();

// Runs generator `name` ("torus", "sphere", "box", "vase", "tree", "plane", "foliage") with parameters from
// the JSON object `params` (null or {} for all defaults). Keys are the parameter names above: torus {major,
// minor, rings, sides}, sphere {radius, stacks, slices}, box {lo, hi}, vase {height, profile, thickness,
// segments, rows}, tree {density, seed, leaf_scale}, plane {size, subdivisions}, foliage {size, leaves or
// density (leaves per unit volume; not both), leaf_size, seed}. Throws voxr::Error starting with `where` (the
// scene file, say) for an unknown name, an unknown key, a wrong type or an out-of-range value, naming the
// key as `path`.key.
TriangleSoup make_generated(const std::string& name, const nlohmann::json& params, const std::string& where,
                            const std::string& path = "params");

}  // namespace voxr
