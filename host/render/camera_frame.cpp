#include "render/camera_frame.h"

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

#include "util/error.h"

namespace voxr {

glm::vec3 CameraFrame::ray_direction(float px, float py) const {
  const float sx = (2.0f * px / float(width) - 1.0f) * tan_half_fov_y * aspect();
  const float sy = (1.0f - 2.0f * py / float(height)) * tan_half_fov_y;
  return glm::normalize(forward + sx * right + sy * up);
}

glm::mat4 CameraFrame::view_projection() const {
  // View: rows right, up, forward; then a perspective whose clip w is the view depth and z/w runs 0..1.
  glm::mat4 view(1.0f);
  for (int c = 0; c < 3; ++c) {
    view[c][0] = right[c];
    view[c][1] = up[c];
    view[c][2] = forward[c];
  }
  view[3][0] = -glm::dot(right, eye);
  view[3][1] = -glm::dot(up, eye);
  view[3][2] = -glm::dot(forward, eye);
  glm::mat4 proj(0.0f);
  proj[0][0] = 1.0f / (tan_half_fov_y * aspect());
  proj[1][1] = 1.0f / tan_half_fov_y;
  proj[2][2] = far_plane / (far_plane - near_plane);
  proj[3][2] = -far_plane * near_plane / (far_plane - near_plane);
  proj[2][3] = 1.0f;
  return proj * view;
}

CameraFrame make_camera_frame(const Camera& camera, const glm::dvec3& anchor, const Bounds& bounds,
                              uint32_t width, uint32_t height) {
  CameraFrame f;
  f.eye = glm::vec3(glm::dvec3(camera.position) - anchor);
  const glm::vec3 target = glm::vec3(glm::dvec3(camera.look_at) - anchor);
  const glm::vec3 ahead = target - f.eye;
  if (!(glm::length(ahead) > 0.0f)) throw Error("camera: look_at equals position");
  f.forward = glm::normalize(ahead);
  const glm::vec3 side = glm::cross(f.forward, camera.up);
  if (!(glm::length(side) > 1e-6f)) throw Error("camera: up is parallel to the view direction");
  f.right = glm::normalize(side);
  f.up = glm::cross(f.right, f.forward);
  if (!(camera.fov_deg > 0.0f && camera.fov_deg < 180.0f)) throw Error("camera: fov_deg must be in (0, 180)");
  f.tan_half_fov_y = std::tan(glm::radians(camera.fov_deg) * 0.5f);
  if (width == 0 || height == 0) throw Error("camera: the image needs at least one pixel");
  f.width = width;
  f.height = height;
  // Depth range of the bounds' corners along forward.
  float lo = std::numeric_limits<float>::max(), hi = 0.0f;
  const glm::vec3 size = bounds.size();
  if (!bounds.empty()) {
    for (int c = 0; c < 8; ++c) {
      const glm::vec3 p((c & 1) ? bounds.hi.x : bounds.lo.x, (c & 2) ? bounds.hi.y : bounds.lo.y,
                        (c & 4) ? bounds.hi.z : bounds.lo.z);
      const float d = glm::dot(p - f.eye, f.forward);
      lo = std::min(lo, d);
      hi = std::max(hi, d);
    }
  }
  const float extent = std::max({size.x, size.y, size.z, 1e-6f});
  f.near_plane = std::max(lo * 0.999f, 1e-4f * extent);
  f.far_plane = std::max(hi * 1.001f, f.near_plane * 2.0f);
  return f;
}

}  // namespace voxr
