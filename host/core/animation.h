// Deforming scenes: a mesh's keyframed transform and procedural per-vertex deformations, and posing the
// whole scene at a time t into one world-space TriangleSoup. Nothing is precomputed for the renderer: every
// frame is a new soup, re-voxelized on the device (render/frame_renderer.h).
//
// A vertex p of a mesh (object space, after subdivision) is placed at time t as
//   world(p, t) = K(t) * S * D(p, t)
// where D applies the mesh's "deform" list in order (object space), S is the mesh's static "transform" and
// K(t) the keyframed transform: scale, rotation and translation interpolated between the two keys around t
// (linearly; the rotation by quaternion slerp along the shorter arc), held before the first and after the
// last key. A key's transform is scale, then rotate about X, Y, Z (degrees), then translate, as "transform".
//
// Deformations measure height h = y - y_base in object space, y_base the lowest vertex of the mesh, so the
// base never moves:
//   sway   p += normalize(axis) * amplitude * h * sin(2 pi frequency_hz t + phase_per_unit h)
//          (tree leaves and trunk sway more the higher they are; amplitude in object units at h = 1)
//   twist  p rotated about the object's Y axis (x = z = 0) by degrees_per_unit * h * sin(2 pi frequency_hz t)
// Both are zero at t = 0: frame 0 is the mesh at rest.
#pragma once

#include <nlohmann/json_fwd.hpp>

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include <string>
#include <vector>

#include "core/triangle_soup.h"

namespace voxr {

struct Scene;

struct TransformKey {
  double time = 0.0;  // seconds
  glm::vec3 scale{1.0f};
  glm::vec3 rotate_deg{0.0f};  // about X, then Y, then Z
  glm::vec3 translate{0.0f};
};

enum class DeformKind { kSway, kTwist };

struct Deform {
  DeformKind kind = DeformKind::kSway;
  float frequency_hz = 1.0f;
  // sway
  float amplitude = 0.0f;            // object units of displacement at height 1
  glm::vec3 axis{1.0f, 0.0f, 0.0f};  // unit sway direction, object space
  float phase_per_unit = 0.0f;       // radians of phase per unit of height
  // twist
  float degrees_per_unit = 0.0f;  // peak rotation per unit of height
};

struct MeshAnimation {
  std::vector<TransformKey> keys;  // strictly increasing times; empty: no keyframed transform
  std::vector<Deform> deforms;     // applied in order
  bool empty() const { return keys.empty() && deforms.empty(); }
};

inline constexpr double kDefaultFps = 24.0;

// A keyframed transform at one time: scale, rotation (unit quaternion) and translation.
struct KeyPose {
  glm::vec3 scale{1.0f};
  glm::quat rotation{1.0f, 0.0f, 0.0f, 0.0f};
  glm::vec3 translate{0.0f};
  glm::mat4 matrix() const;  // T * R * S
};

// The keys' transform at time `t` (seconds): exactly a key's values at its time, interpolated between keys,
// held outside them. `keys` must be non-empty with increasing times.
KeyPose interpolate_keys(const std::vector<TransformKey>& keys, double t);

// Object-space position `p` of a mesh whose lowest vertex has y = `base_y`, deformed by `deforms` at time t.
glm::dvec3 deform_point(const std::vector<Deform>& deforms, glm::dvec3 p, double base_y, double t);

// Parses a mesh's "animation" object (scene.h lists the keys); `path` is its key path, e.g.
// "meshes[1].animation". Throws voxr::Error naming `where` and the key path at fault.
MeshAnimation parse_mesh_animation(const nlohmann::json& value, const std::string& where,
                                   const std::string& path);
// Parses the scene's "animation" object: its frames per second (> 0, default kDefaultFps).
double parse_scene_animation(const nlohmann::json& value, const std::string& where);

// True when some mesh has an "animation" (keys or deformations): its triangles depend on time.
bool is_animated(const Scene& scene);

// The whole scene posed at time `t` (seconds): every mesh in world space with its material ids, in scene
// order, positions relative to `anchor`. Triangles and vertex counts are the same at every t.
// `out` is overwritten (its allocations are reused: a renderer reading it in place must be done with it).
// Throws voxr::Error naming the scene when a posed vertex is not finite or lies beyond 1e30 (the mesh
// readers' limit, text::kMaxCoordinate): keys and deformations that are each finite can multiply past it.
void pose_scene(const Scene& scene, double t, const glm::dvec3& anchor, TriangleSoup& out);
TriangleSoup pose_scene(const Scene& scene, double t, const glm::dvec3& anchor);

// The anchor every frame of an animated scene uses: chosen (choose_anchor) for the world bounds at t = 0,
// so the grids and cameras fitted to frame 0 do not jump.
glm::dvec3 animation_anchor(const Scene& scene);

}  // namespace voxr
