#include "cli/parse_args.h"

#include <cmath>
#include <sstream>

#include "core/grid_spec.h"
#include "util/error.h"

namespace voxr::cli {

std::vector<double> parse_numbers(const std::string& text, size_t count, const std::string& flag) {
  std::vector<double> values;
  std::stringstream in(text);
  std::string item;
  while (std::getline(in, item, ',')) {
    size_t used = 0;
    double v = 0.0;
    try {
      v = std::stod(item, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used == 0 || used != item.size() || !std::isfinite(v))
      fail("{} '{}': '{}' is not a finite number", flag, text, item);
    values.push_back(v);
  }
  if (values.size() != count) fail("{} '{}': expected {} comma-separated numbers", flag, text, count);
  return values;
}

glm::uvec3 parse_dims(const std::string& text, const std::string& flag) {
  const std::vector<double> v = parse_numbers(text, 3, flag);
  glm::uvec3 dims;
  for (int a = 0; a < 3; ++a) {
    if (v[a] < 1 || v[a] > kMaxGridDim || v[a] != std::floor(v[a]))
      fail("{} '{}': each dimension must be an integer in 1..{}", flag, text, kMaxGridDim);
    dims[a] = uint32_t(v[a]);
  }
  return dims;
}

WorldBox parse_bounds(const std::string& text, const std::string& flag) {
  const std::vector<double> v = parse_numbers(text, 6, flag);
  const WorldBox b(glm::dvec3(v[0], v[1], v[2]), glm::dvec3(v[3], v[4], v[5]));
  for (int a = 0; a < 3; ++a)
    if (!(b.lo[a] < b.hi[a]))
      fail("{} '{}': the low corner must be below the high corner on every axis", flag, text);
  return b;
}

glm::uvec2 parse_size(const std::string& text, const std::string& flag) {
  // A side as a finite number, else NaN (the message then names the whole value, not the side).
  const auto side = [](const std::string& part) {
    size_t used = 0;
    double v = std::nan("");
    try {
      v = std::stod(part, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    return used != 0 && used == part.size() && std::isfinite(v) ? v : std::nan("");
  };
  const size_t x = text.find_first_of("xX");
  const double w = x == std::string::npos ? std::nan("") : side(text.substr(0, x));
  const double h = x == std::string::npos ? std::nan("") : side(text.substr(x + 1));
  if (std::isnan(w) || std::isnan(h)) fail("{} '{}': expected WIDTHxHEIGHT, e.g. 640x480", flag, text);
  if (w < 1 || h < 1 || w > 16384 || h > 16384 || w != std::floor(w) || h != std::floor(h))
    fail("{} '{}': width and height must be whole numbers in 1..16384", flag, text);
  return {uint32_t(w), uint32_t(h)};
}

}  // namespace voxr::cli
