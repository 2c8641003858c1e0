// Parsers for the CLI's composite values ("X,Y,Z", "x0,y0,z0,x1,y1,z1"); errors name the flag.
#pragma once

#include <glm/glm.hpp>

#include <string>
#include <vector>

#include "core/grid_spec.h"

namespace voxr::cli {

std::vector<double> parse_numbers(const std::string& text, size_t count, const std::string& flag);
glm::uvec3 parse_dims(const std::string& text, const std::string& flag);
WorldBox parse_bounds(const std::string& text, const std::string& flag);
// "640x480" (or "640X480"): an image size, each side a whole number in 1..16384.
glm::uvec2 parse_size(const std::string& text, const std::string& flag);

}  // namespace voxr::cli
