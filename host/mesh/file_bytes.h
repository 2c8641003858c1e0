// A file's bytes: mapped when it is a regular file, read otherwise (pipes). Mapping copies nothing and needs
// no fresh pages; reading a 40 MB mesh into a new buffer took longer than parsing it.
#pragma once

#include <filesystem>
#include <string>
#include <string_view>

namespace voxr {

class FileBytes {
 public:
  // Throws voxr::Error naming the file when it cannot be opened or read.
  explicit FileBytes(const std::filesystem::path& file);
  ~FileBytes();
  FileBytes(const FileBytes&) = delete;
  FileBytes& operator=(const FileBytes&) = delete;

  std::string_view view() const {
    return map_ ? std::string_view(static_cast<const char*>(map_), size_) : copy_;
  }

 private:
  void* map_ = nullptr;
  size_t size_ = 0;
  std::string copy_;
};

}  // namespace voxr
