#include "core/default_scene.h"

namespace voxr {

std::string_view default_scene_json() {
  // Keep identical to data/scenes/default.json (DefaultScene tests compare them).
  static constexpr std::string_view kJson = R"json({
  "materials": [
    {"name": "glass", "kind": "dielectric", "ior": 1.5, "absorption": [1.1, 0.35, 0.08]},
    {"name": "vase_glass", "kind": "dielectric", "ior": 1.45, "absorption": [1.4, 0.3, 1.1]},
    {"name": "floor", "kind": "opaque", "color": [0.75, 0.75, 0.72]},
    {"name": "clay", "kind": "opaque", "color": [0.8, 0.35, 0.2]},
    {"name": "bark", "kind": "opaque", "color": [0.35, 0.22, 0.12]},
    {"name": "leaf", "kind": "sheet", "color": [0.3, 0.6, 0.2], "transmittance": [0.45, 0.8, 0.35]}
  ],
  "meshes": [
    {"generator": "plane", "params": {"size": [8, 8], "subdivisions": 1}, "material": "floor"},
    {"generator": "torus", "params": {"major": 1.0, "minor": 0.4, "rings": 20, "sides": 20},
     "material": "glass", "transform": {"rotate_deg": [90, 0, 0], "translate": [0, 1.6, 0]}},
    {"generator": "vase", "params": {"height": 1.0, "thickness": 0.03, "segments": 48, "rows": 32},
     "material": "vase_glass", "transform": {"scale": 1.5, "translate": [-2.6, 0, -0.4]}},
    {"generator": "sphere", "params": {"radius": 0.6, "stacks": 16, "slices": 32},
     "material": "clay", "transform": {"translate": [2.4, 0.6, 0.4]}},
    {"generator": "tree", "params": {"density": 0.5, "seed": 7},
     "material": ["bark", "leaf"], "transform": {"scale": 1.8, "translate": [1.2, 0, -2.6]}}
  ],
  "light": {"type": "point", "position": [3, 8, 5], "intensity": [75, 75, 75]},
  "camera": {"position": [0, 3.2, 8.5], "look_at": [0, 1.2, 0], "up": [0, 1, 0], "fov_deg": 45,
             "width": 512, "height": 512},
  "environment": {"color": [0.25, 0.28, 0.33]}
}
)json";
  return kJson;
}

Scene default_scene() {
  return parse_scene(default_scene_json(), "built-in default scene", {});
}

}  // namespace voxr
