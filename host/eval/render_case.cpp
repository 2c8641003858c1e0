#include "eval/render_case.h"

#include "render/render_scene.h"
#include "util/error.h"

namespace voxr {

RenderCase::RenderCase(Scene scene, uint32_t width, uint32_t height)
    : scene_(std::move(scene)),
      soup_(take_scene_triangles(scene_)),
      environment_(make_environment_map(scene_.environment)),
      reference_(soup_, scene_.materials) {
  if (width == 0 || height == 0) fail("{}: an empty image size {}x{}", scene_.source, width, height);
  validate_soup(soup_, scene_.source);
  camera_ = make_camera_frame(scene_.camera, soup_.anchor, soup_.bounds(), width, height);
  light_ = render_light(scene_.light, environment_.mean(), soup_.anchor);
  render_materials_ = voxr::render_materials(scene_.materials);
}

}  // namespace voxr
