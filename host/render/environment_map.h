// What rays that leave the scene see (kernels/environment.h): an equirectangular RGBA image, one of
//   constant    a 1 x 1 image of the scene's "environment": {"color": ...}
//   checker     the built-in procedural lat-long checker ("environment": {"procedural": "checker"}): 32 x 16
//               cells of 11.25 degrees, hue by longitude, bright and dark alternating, the lower half darker,
//               so directions are told apart and tests need no files
//   image       an equirectangular file (.exr, .hdr, .png; PNG decoded from sRGB: io/image_file.h)
// The same lookup runs on the device (shade.cl) and on the host (the reference).
#pragma once

#include <glm/glm.hpp>

#include <cstdint>
#include <string>
#include <vector>

#include "core/scene.h"

namespace voxr {

class EnvironmentMap {
 public:
  // A constant environment of `color` (RGB >= 0).
  static EnvironmentMap constant(const glm::vec3& color);
  // The built-in lat-long checker, `width` x width/2 texels.
  static EnvironmentMap checker(uint32_t width = 512);
  // An image of width x height RGBA texels (row 0 = straight up). Throws voxr::Error naming `source` for an
  // empty image, a size mismatch or a negative or non-finite texel.
  static EnvironmentMap from_pixels(uint32_t width, uint32_t height, std::vector<glm::vec4> rgba,
                                    const std::string& source);

  // Radiance (RGB) seen along `direction` (world, need not be unit; zero looks straight up).
  glm::vec3 lookup(const glm::vec3& direction) const;
  // Solid-angle-weighted mean radiance: the ambient term opaque surfaces get (RenderLight::ambient).
  glm::vec3 mean() const { return mean_; }

  uint32_t width() const { return width_; }
  uint32_t height() const { return height_; }
  const std::vector<glm::vec4>& pixels() const { return pixels_; }  // width * height, row-major
  const std::string& source() const { return source_; }             // "color", "checker" or the file

 private:
  uint32_t width_ = 1, height_ = 1;
  std::vector<glm::vec4> pixels_{glm::vec4(0.5f, 0.5f, 0.5f, 1.0f)};
  glm::vec3 mean_{0.5f};
  std::string source_ = "color";
};

// The scene's environment: the image file (Environment::image), the procedural one, or the colour. Throws
// voxr::Error naming the image file when it cannot be read or is not an environment (negative, non-finite).
EnvironmentMap make_environment_map(const Environment& environment);

}  // namespace voxr
