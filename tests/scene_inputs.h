// Inputs the scene-input tests generate (issue 20, kinds 5 and 8): the floor-and-box mesh as a two-primitive
// glTF and as a two-group OBJ, its twin of generators, and a floor-and-sphere scene translated anywhere.
#pragma once

#include <glm/glm.hpp>

#include <filesystem>
#include <string>

namespace voxr::test {

// Writes `name` (glTF 2.0 JSON) and its buffer beside it in `dir`: one mesh of two primitives, the floor
// [-3, 3] x {0} x [-3, 3] (2 triangles, material 0) and the box [-0.5, 0.5] x [0, 1] x [-0.5, 0.5]
// (12 triangles, material 1), both wound outward. Returns the glTF's path.
std::filesystem::path write_floor_and_box_gltf(const std::filesystem::path& dir, const std::string& name);
// The same faces as OBJ text, translated by `shift` (every digit written): the floor before any usemtl, the
// box after `usemtl box`.
std::string floor_and_box_obj(const glm::dvec3& shift = glm::dvec3(0.0));
// The scene of issue 20's r05: the mesh `mesh_file` (floor and box) with materials ["floor", "red"], or,
// when `mesh_file` is empty, its twin of generators (plane and box); a directional light and a camera.
std::string floor_and_box_scene(const std::string& mesh_file);

// Issue 20's r08: a 6 x 6 floor and a red sphere of radius 0.5 at (0, 0.6, 0), translated by `shift`; no
// camera; a directional light when `directional_light`, else no light either (the defaults frame it).
std::string far_scene_json(const glm::dvec3& shift, bool directional_light);

}  // namespace voxr::test
