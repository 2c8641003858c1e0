// Preprocessor definitions a kernel program is built with, as (name, value) pairs: -Dname=value.
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace voxr {

using Defines = std::vector<std::pair<std::string, std::string>>;

}  // namespace voxr
