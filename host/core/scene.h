// A scene: meshes with materials, one light, one camera, an environment and how to fit the grid.
//
// The scene file format (JSON), every key with its default and range, the generators, animation and the
// example scenes in data/scenes/: docs/scene-format.md. Mesh file paths are relative to the scene file's
// folder, else looked up in $VOXR_MESH_DIR (default data/meshes). Without "light", "camera" or
// "environment", defaults frame the scene's bounds (default_camera, default_light, kDefaultEnvironment). An
// animated scene's bounds, default camera and light, fitted grid and scene_triangles are those of t = 0;
// pose_scene (animation.h) gives the triangles at any time.
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
#include "core/material.h"
#include "core/triangle_soup.h"
#include "util/json_reader.h"

namespace voxr {

// Positions are world coordinates in double, as the scene file gives them (a scene 1e8 from the origin keeps
// its light and camera where they were written; RenderCase makes them anchor-relative floats).
struct Light {
  std::string type = "point";              // "point" | "directional"
  glm::dvec3 position{0.0};                // point
  glm::vec3 direction{0.0f, -1.0f, 0.0f};  // directional: unit vector, the way the light travels
  glm::vec3 intensity{1.0f};  // point: irradiance at distance d is intensity / d^2; directional: irradiance
};

struct Camera {
  glm::dvec3 position{0.0, 0.0, 5.0};
  glm::dvec3 look_at{0.0};
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
  // About the whole scene, one line each (a scene too small for the precision of its coordinates);
  // the meshes' own are in MeshInstance::warnings.
  std::vector<std::string> warnings;
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
// The scene load_input makes of a mesh file, for a soup read elsewhere (the public API's arrays): `source`
// names the scene and its mesh, `warnings` are the mesh's.
Scene scene_from_mesh(TriangleSoup soup, const std::string& source, std::vector<std::string> warnings = {});

// Every mesh in world space with its material ids, in scene order; positions relative to an anchor chosen
// for the whole scene (choose_anchor).
TriangleSoup scene_triangles(const Scene& scene);

// The same triangles, taking the soup of a single mesh placed as it is instead of copying it (a 1 M-triangle
// soup is 36 MB); that mesh's soup is left empty. For callers done with the scene's meshes.
TriangleSoup take_scene_triangles(Scene& scene);

// World-space bounds of the vertices all meshes' triangles use, in double (lo > hi when there are none).
WorldBox scene_world_bounds(const Scene& scene);
// The same rounded to float.
Bounds scene_bounds(const Scene& scene);

// Scale, then rotate about X, Y and Z (degrees, in that order), then translate.
glm::mat4 make_transform(glm::vec3 scale, glm::vec3 rotate_deg, glm::vec3 translate);

// Camera in front of `bounds` (on +Z, slightly raised) looking at its centre with a 45 degree field of
// view, far enough to see all of it. Fitted in double: a scene far from the origin gets the camera of the
// same scene at the origin, translated (bounds with lo > hi: the unit sphere's).
Camera default_camera(const WorldBox& bounds);
// Point light above, in front of and to the right of `bounds`, bright enough for irradiance ~1 at the
// centre; fitted in double as default_camera is.
Light default_light(const WorldBox& bounds);

// One line naming `label` when the extent of `bounds` (its longest side) spans fewer than 65 536 steps of a
// double at its largest coordinate (a 6-unit scene 1e13 from the origin: steps of 0.002): its positions are
// quantised, and where a step exceeds the extent the scene collapses; empty otherwise.
std::string precision_warning(const WorldBox& bounds, const std::string& label);

}  // namespace voxr
