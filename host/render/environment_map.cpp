#include "render/environment_map.h"

#include <fmt/format.h>

#include <cmath>

#include "environment.h"
#include "io/image_file.h"
#include "util/error.h"
#include "util/file_extension.h"

namespace voxr {

namespace {

// Hue h in [0, 1) at full saturation, value v.
glm::vec3 hue(float h, float v) {
  const float r = std::clamp(std::abs(h * 6.0f - 3.0f) - 1.0f, 0.0f, 1.0f);
  const float g = std::clamp(2.0f - std::abs(h * 6.0f - 2.0f), 0.0f, 1.0f);
  const float b = std::clamp(2.0f - std::abs(h * 6.0f - 4.0f), 0.0f, 1.0f);
  return v * (0.25f + 0.75f * glm::vec3(r, g, b));
}

glm::vec3 solid_angle_mean(uint32_t width, uint32_t height, const std::vector<glm::vec4>& pixels) {
  glm::dvec3 sum(0.0);
  double weight = 0.0;
  for (uint32_t y = 0; y < height; ++y) {
    const double theta0 = M_PI * y / height, theta1 = M_PI * (y + 1) / height;
    const double w = std::cos(theta0) - std::cos(theta1);  // the row's share of the sphere, per column
    for (uint32_t x = 0; x < width; ++x) sum += w * glm::dvec3(pixels[size_t(y) * width + x]);
    weight += w * width;
  }
  return glm::vec3(sum / weight);
}

}  // namespace

EnvironmentMap EnvironmentMap::constant(const glm::vec3& color) {
  return from_pixels(1, 1, {glm::vec4(color, 1.0f)}, "color");
}

EnvironmentMap EnvironmentMap::checker(uint32_t width) {
  const uint32_t w = std::max<uint32_t>(width, 16), h = w / 2;
  std::vector<glm::vec4> px(size_t(w) * h);
  for (uint32_t y = 0; y < h; ++y)
    for (uint32_t x = 0; x < w; ++x) {
      const uint32_t cx = x * 32 / w, cy = y * 16 / h;
      const float v = ((cx + cy) & 1) ? 1.0f : 0.35f;
      glm::vec3 c = hue((float(cx / 2) + 0.5f) / 16.0f, v);
      const float polar = (float(y) + 0.5f) / float(h);  // 0 up, 1 down
      if (polar > 0.5f) c *= 0.6f;                       // the ground half darker, as under a sky
      px[size_t(y) * w + x] = glm::vec4(c, 1.0f);
    }
  return from_pixels(w, h, std::move(px), "checker");
}

EnvironmentMap EnvironmentMap::from_pixels(uint32_t width, uint32_t height, std::vector<glm::vec4> rgba,
                                           const std::string& source) {
  if (width == 0 || height == 0) fail("{}: the environment image is empty", source);
  if (rgba.size() != size_t(width) * height)
    fail("{}: {} texels for a {}x{} environment", source, rgba.size(), width, height);
  for (size_t i = 0; i < rgba.size(); ++i)
    for (int c = 0; c < 3; ++c)
      if (!std::isfinite(rgba[i][c]) || rgba[i][c] < 0.0f)
        fail("{}: environment texel ({}, {}) has radiance {} (must be finite and >= 0)", source, i % width,
             i / width, rgba[i][c]);
  EnvironmentMap map;
  map.width_ = width;
  map.height_ = height;
  map.pixels_ = std::move(rgba);
  map.mean_ = solid_angle_mean(width, height, map.pixels_);
  map.source_ = source;
  return map;
}

glm::vec3 EnvironmentMap::lookup(const glm::vec3& direction) const {
  float rgb[3];
  voxr_environment_lookup(&pixels_[0].x, width_, height_, direction.x, direction.y, direction.z, rgb);
  return glm::vec3(rgb[0], rgb[1], rgb[2]);
}

EnvironmentMap make_environment_map(const Environment& environment) {
  if (!environment.image.empty()) {
    const std::string ext = lower_extension(environment.image);
    if (ext != ".exr" && ext != ".hdr" && ext != ".png")
      fail("{}: unsupported environment image format '{}' (supported: .exr, .hdr, .png)", environment.image,
           ext);
    ImageRgba image = read_image(environment.image);
    return EnvironmentMap::from_pixels(image.width, image.height, std::move(image.pixels), environment.image);
  }
  if (environment.procedural == "checker") return EnvironmentMap::checker();
  if (!environment.procedural.empty()) fail("unknown procedural environment '{}'", environment.procedural);
  return EnvironmentMap::constant(environment.color);
}

}  // namespace voxr
