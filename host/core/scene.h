// A scene: meshes with materials, one light, one camera, an environment colour and how to fit the grid.
//
// Scene file format (JSON; // and /* */ comments allowed). Every key is optional unless marked required;
// an unknown or repeated key anywhere is an error naming its path (e.g. "scene.json: unknown key
// 'meshes[1].materail' (did you mean 'meshes[1].material'?)"); so are wrong types and out-of-range values.
//
//   {
//     "materials": [                                  default: one opaque material "default"
//       {"name": "floor", "kind": "opaque",           name (required, unique), kind (required)
//        "color": [0.8, 0.8, 0.8]},                   opaque: color in [0,1]             (0.8)
//       {"name": "glass", "kind": "dielectric",
//        "ior": 1.5, "absorption": [0.1, 0.2, 0.3]},  dielectric: ior > 0 (1.5), absorption >= 0 per unit (0)
//       {"name": "leaf", "kind": "sheet",
//        "color": [0.3, 0.6, 0.2],                    sheet: color in [0,1] (0.8),
//        "transmittance": [0.5, 0.8, 0.4]}            transmittance per crossing in [0,1] (1)
//     ],                                              (a key of another kind is an error)
//     "meshes": [                                     required, at least one
//       {"file": "../meshes/bunny.obj",               a mesh file (.obj .off .ply .stl), see below, or
//        "material": "glass",                         a material name, or a list of names, one per
//                                                     material id the mesh carries (["bark", "leaf"] for
//                                                     a tree); default: the first material
//        "subdivide": 0,                              midpoint subdivision levels (0..8), before transforming
//        "transform": {"scale": 1.0,                  a number or [x, y, z], no component 0
//                      "rotate_deg": [0, 0, 0],       about X, then Y, then Z, in degrees
//                      "translate": [0, 0, 0]},       applied in this order: scale, rotate, translate
//        "animation": {                               optional; makes the scene deforming (animation.h)
//          "keys": [{"time": 0,                       seconds >= 0, strictly increasing (required)
//                    "scale": 1, "rotate_deg": [0, 0, 0], "translate": [0, 0, 0]},  as "transform"
//                   {"time": 2, "translate": [1, 0, 0]}],  interpolated linearly, rotation by quaternion
//                                                     slerp; held before the first and after the last key;
//                                                     applied after "transform": world = K(t) * transform * p
//          "deform": [                                per-vertex, object space, before "transform", in order;
//                                                     h = height above the mesh's lowest vertex
//            {"kind": "sway", "amplitude": 0.05,      required: object units of displacement at h = 1
//             "frequency_hz": 0.5,                    required, > 0
//             "axis": [1, 0, 0],                      non-zero sway direction ([1, 0, 0]); the offset is
//             "phase_per_unit": 0},                   axis * amplitude * h * sin(2 pi f t + phase_per_unit h)
//            {"kind": "twist", "degrees_per_unit": 30, required: peak rotation about the object's Y axis
//             "frequency_hz": 0.25}]}},               per unit of h; angle = deg * h * sin(2 pi f t), f > 0
//       {"generator": "torus",                        torus | sphere | box | vase | tree | plane | foliage
//        "params": {"major": 1, "minor": 0.4},        generator parameters (generators.h)
//        "material": "floor"}
//     ],
//     "light": {"type": "point",                      required when "light" is given: point | directional
//               "position": [0, 5, 5],                point: required
//               "direction": [0, -1, 0],              directional: required, non-zero, the way light travels
//               "intensity": [1, 1, 1]},              >= 0 (1); point lights fall off as 1/distance^2
//     "camera": {"position": [0, 1, 5],               required when "camera" is given
//                "look_at": [0, 0, 0],                required when "camera" is given, != position
//                "up": [0, 1, 0],                     not parallel to look_at - position
//                "fov_deg": 45,                       vertical field of view in (0, 180)
//                "width": 512, "height": 512},        image size, 1..16384
//     "environment": {"color": [0.5, 0.5, 0.5]},      exactly one of: color >= 0,
//                    {"image": "sky.exr"},            an equirectangular .exr/.hdr/.png (relative to the
//                                                     scene file), row 0 straight up, centre column -z,
//                    {"procedural": "checker"},       or the built-in lat-long checker
//     "grid": {"res": 256,                            voxels along the longest axis (1..16384), or
//              "dims": [256, 128, 256],               exact dimensions (not both)
//              "bounds": [x0, y0, z0, x1, y1, z1],    world box, x0 < x1 etc.; default: fitted to the scene
//              "margin_voxels": 0.25}                 >= 0, around fitted bounds (faces kept off ties)
//     "animation": {"fps": 24}                        frames per second of `voxr render --frames` (24)
//   }
//
// Mesh file paths are relative to the scene file's folder. A path "$VOXR_MESH_DIR/NAME", or a relative path
// not found next to the scene, is looked up in the folder named by the environment variable VOXR_MESH_DIR
// (default: data/meshes under the current directory). Material ids are indices into "materials".
// Without "light", "camera" or "environment", defaults frame the scene's bounds (default_camera,
// default_light, kDefaultEnvironment). An animated scene's bounds, default camera and light, fitted grid and
// scene_triangles are those of t = 0; pose_scene (animation.h) gives the triangles at any time.
#pragma once

#include <nlohmann/json_fwd.hpp>

#include <glm/glm.hpp>

#include <cstdint>
#include <filesystem>
#include <initializer_list>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/animation.h"
#include "core/grid_spec.h"
#include "core/json_reader.h"
#include "core/material.h"
#include "core/triangle_soup.h"

namespace voxr {

struct Light {
  std::string type = "point";              // "point" | "directional"
  glm::vec3 position{0.0f};                // point
  glm::vec3 direction{0.0f, -1.0f, 0.0f};  // directional: unit vector, the way the light travels
  glm::vec3 intensity{1.0f};  // point: irradiance at distance d is intensity / d^2; directional: irradiance
};

struct Camera {
  glm::vec3 position{0.0f, 0.0f, 5.0f};
  glm::vec3 look_at{0.0f};
  glm::vec3 up{0.0f, 1.0f, 0.0f};
  float fov_deg = 45.0f;  // vertical
  uint32_t width = 512, height = 512;
};

// What rays leaving the scene see (render/environment_map.h reads it): one of a constant colour, an
// equirectangular image file (resolved path) or a procedural environment ("checker").
struct Environment {
  glm::vec3 color{0.5f};
  std::string image;       // .exr, .hdr or .png, latitude-longitude, row 0 straight up
  std::string procedural;  // "checker" or empty
};

inline constexpr glm::vec3 kDefaultEnvironment{0.5f};

struct MeshInstance {
  std::string source;  // the mesh file's resolved path, or "generator:NAME"
  TriangleSoup soup;   // object space, after subdivision
  glm::mat4 transform{1.0f};
  // Scene material id given to every triangle, or TriangleSoup::kKeepMaterial when the soup's own ids are
  // already scene material ids (a "material" list remaps them at load time).
  uint32_t material = 0;
  MeshAnimation animation;            // empty: the mesh does not move
  std::vector<std::string> warnings;  // from reading the file (mesh_loader.h), one line each
};

struct Scene {
  std::vector<Material> materials;
  std::vector<MeshInstance> meshes;
  Light light;
  Camera camera;
  Environment environment;
  GridRequest grid;
  bool grid_given = false;   // the scene file had a "grid" object
  double fps = kDefaultFps;  // frames per second of an animation
  std::string source;        // the scene file, the mesh file, or a description of a built-in scene
};

// Reads a scene file. Throws voxr::Error naming the file and the key path at fault (or the line and
// column for JSON syntax errors); mesh loading errors are reported with the mesh's key path too.
Scene load_scene(const std::filesystem::path& json_file);

// Parses scene JSON text. `label` names the source in errors and becomes Scene::source; relative mesh
// paths resolve against `base_dir`.
Scene parse_scene(std::string_view json_text, const std::string& label,
                  const std::filesystem::path& base_dir);

// `.json` -> load_scene. Any other extension: the mesh file as a scene with one opaque material
// "default", identity transform and default light, camera and environment framing the mesh.
Scene load_input(const std::filesystem::path& input);

// Every mesh in world space with its material ids, in scene order; positions relative to an anchor chosen
// for the whole scene (choose_anchor).
TriangleSoup scene_triangles(const Scene& scene);

// The same triangles, taking the soup of a single mesh placed as it is instead of copying it (a 1 M-triangle
// soup is 36 MB); that mesh's soup is left empty. For callers done with the scene's meshes.
TriangleSoup take_scene_triangles(Scene& scene);

// World-space bounds of all meshes (float: for framing cameras and lights).
Bounds scene_bounds(const Scene& scene);

// Scale, then rotate about X, Y and Z (degrees, in that order), then translate.
glm::mat4 make_transform(glm::vec3 scale, glm::vec3 rotate_deg, glm::vec3 translate);

// Camera in front of `bounds` (on +Z, slightly raised) looking at its centre with a 45 degree field of
// view, far enough to see all of it.
Camera default_camera(const Bounds& bounds);
// Point light above, in front of and to the right of `bounds`, bright enough for irradiance ~1 at the centre.
Light default_light(const Bounds& bounds);

}  // namespace voxr
