// The camera as every renderer uses it: a pinhole at `eye` looking along `forward`, positions relative to
// the scene's anchor (TriangleSoup::anchor), pixel (x, y) with the top row first and its centre at
// (x + 0.5, y + 0.5). The kernel rasterizer and the Embree reference both derive their rays and matrices from
// this one struct, so they see the same pixels.
#pragma once

#include <glm/glm.hpp>

#include <cstdint>

#include "core/scene.h"

namespace voxr {

struct CameraFrame {
  glm::vec3 eye{0.0f};                   // anchor-relative
  glm::vec3 forward{0.0f, 0.0f, -1.0f};  // unit
  glm::vec3 right{1.0f, 0.0f, 0.0f};     // unit, image x
  glm::vec3 up{0.0f, 1.0f, 0.0f};        // unit, image -y (rows go down)
  float tan_half_fov_y = 0.41421356f;    // vertical
  uint32_t width = 1, height = 1;
  float near_plane = 0.01f, far_plane = 100.0f;  // view depths (along forward) the clip space spans

  float aspect() const { return float(width) / float(height); }
  // Unit direction of the ray through image point (px, py) in pixels (a pixel's centre: x + 0.5, y + 0.5).
  glm::vec3 ray_direction(float px, float py) const;
  // Anchor-relative world -> clip space (column-major, glm): x_ndc, y_ndc in [-1, 1] with y_ndc = +1 at the
  // top row, z_ndc = z_clip / w_clip in [0, 1] from near_plane to far_plane, w_clip = view depth.
  glm::mat4 view_projection() const;
};

// The frame of `camera` (world coordinates) for a scene whose positions are relative to `anchor`, with
// `width` x `height` pixels; near and far planes enclose `bounds` (anchor-relative), the near plane at least
// 1e-4 of the bounds' size from the eye. Throws voxr::Error for a degenerate camera.
CameraFrame make_camera_frame(const Camera& camera, const glm::dvec3& anchor, const Bounds& bounds,
                              uint32_t width, uint32_t height);

}  // namespace voxr
