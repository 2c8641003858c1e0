// A rendered image on the host: linear RGBA floats, row-major with the top row first (the device image read
// back, or a file decoded to linear). Radiance units are the renderer's (1 = white under a unit light).
#pragma once

#include <glm/glm.hpp>

#include <cstdint>
#include <vector>

namespace voxr {

struct ImageRgba {
  uint32_t width = 0, height = 0;
  std::vector<glm::vec4> pixels;  // width * height, pixel (x, y) at y * width + x

  ImageRgba() = default;
  ImageRgba(uint32_t w, uint32_t h, glm::vec4 fill = glm::vec4(0.0f))
      : width(w), height(h), pixels(size_t(w) * h, fill) {}
  glm::vec4& at(uint32_t x, uint32_t y) { return pixels[size_t(y) * width + x]; }
  const glm::vec4& at(uint32_t x, uint32_t y) const { return pixels[size_t(y) * width + x]; }
};

}  // namespace voxr
