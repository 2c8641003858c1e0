#include "cli/parse_args.h"

#include <cmath>
#include <sstream>

#include "core/error.h"
#include "core/grid_spec.h"

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
  const size_t x = text.find_first_of("xX");
  if (x == std::string::npos) fail("{} '{}': expected WIDTHxHEIGHT, e.g. 640x480", flag, text);
  const std::vector<double> w = parse_numbers(text.substr(0, x), 1, flag);
  const std::vector<double> h = parse_numbers(text.substr(x + 1), 1, flag);
  if (w[0] < 1 || h[0] < 1 || w[0] > 16384 || h[0] > 16384 || w[0] != std::floor(w[0]) ||
      h[0] != std::floor(h[0]))
    fail("{} '{}': width and height must be whole numbers in 1..16384", flag, text);
  return {uint32_t(w[0]), uint32_t(h[0])};
}

}  // namespace voxr::cli
