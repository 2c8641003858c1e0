// Preprocessor definitions a kernel program is built with, as (name, value) pairs: -Dname=value.
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace voxr {

using Defines = std::vector<std::pair<std::string, std::string>>;

// `defines` with name=value added.
inline Defines with(Defines defines, const std::string& name, const std::string& value) {
  defines.emplace_back(name, value);
  return defines;
}

}  // namespace voxr
