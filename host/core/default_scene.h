// The built-in scene `voxr voxelize` uses when given no input: needs no files, exercises every material
// kind. A glass torus (800 triangles) stands on an opaque floor, beside a closed dielectric vase, an opaque
// sphere and a small tree whose leaves are sheets. data/scenes/default.json holds the same JSON (a test
// keeps them equal).
#pragma once

#include <string_view>

#include "core/scene.h"

namespace voxr {

// The scene file text default_scene() parses.
std::string_view default_scene_json();

// parse_scene(default_scene_json()), with Scene::source "built-in default scene".
Scene default_scene();

}  // namespace voxr
