// A file's extension in lower case with the dot ("" when it has none): formats are chosen by extension in
// any case (bunny.OBJ, out.PNG).
#pragma once

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <string>

namespace voxr {

inline std::string lower_extension(const std::filesystem::path& file) {
  std::string ext = file.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return ext;
}

}  // namespace voxr
