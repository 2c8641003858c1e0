// A render case (DESIGN.md eval/: "a render or voxelize case against its reference"): one scene made ready to
// render at a size, the same way for the CLI, the benchmarks and the stability suite: load -> triangle soup
// (validated) -> camera -> light -> materials -> environment, and the exact reference built on first need.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "core/material.h"
#include "core/scene.h"
#include "core/triangle_soup.h"
#include "reference/embree_reference.h"
#include "render/camera_frame.h"
#include "render/environment_map.h"
#include "voxr_layout.h"

namespace voxr {

class RenderCase {
 public:
  // Takes the scene's triangles (take_scene_triangles) and places camera and light for width x height
  // pixels. Throws voxr::Error for an empty or non-finite soup (validate_soup) or an empty size.
  RenderCase(Scene scene, uint32_t width, uint32_t height);
  RenderCase(RenderCase&&) = delete;  // the reference holds references to soup and materials

  const Scene& scene() const { return scene_; }
  const TriangleSoup& soup() const { return soup_; }
  const std::vector<Material>& materials() const { return scene_.materials; }
  const std::vector<RenderMaterial>& render_materials() const { return render_materials_; }
  const EnvironmentMap& environment() const { return environment_; }
  const CameraFrame& camera() const { return camera_; }
  const RenderLight& light() const { return light_; }

  // The exact reference of the soup (its BVH built on first need); FrameRenderer::set_scene takes it.
  EmbreeReference& reference() { return reference_; }

 private:
  Scene scene_;
  TriangleSoup soup_;
  EnvironmentMap environment_;
  CameraFrame camera_;
  RenderLight light_;
  std::vector<RenderMaterial> render_materials_;
  EmbreeReference reference_;
};

}  // namespace voxr
