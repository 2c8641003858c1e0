// Compiled OpenCL programs kept on disk between processes. Building a program from source costs tens of
// milliseconds even when the driver has its own cache (PoCL preprocesses and hashes the source every
// time); a program created from its stored binary builds in a few. A fresh `voxr` process thus pays for
// compilation once per machine, not once per run.
//
// Folder: $VOXR_CACHE_DIR, else $XDG_CACHE_HOME/voxr, else $HOME/.cache/voxr. An entry is keyed by a
// 64-bit FNV-1a hash of (platform, device, driver version, build options, expanded source) and stores that
// key text in full, so a hash collision or a stale entry is detected and rebuilt, never used. Entries are
// written to a temporary file and renamed, so concurrent processes never read half a file. A missing,
// unwritable or corrupt cache only costs a build from source; it is never an error.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace voxr {

class ProgramCache {
 public:
  // The folder from the environment (see above); no cache when none can be found.
  ProgramCache();
  explicit ProgramCache(std::optional<std::filesystem::path> folder) : folder_(std::move(folder)) {}

  // The stored binary for `key` (the full key text), or nothing.
  std::optional<std::vector<unsigned char>> load(const std::string& key) const;
  // Stores `binary` for `key`; failures are ignored (the cache is an optimisation).
  void store(const std::string& key, const std::vector<unsigned char>& binary) const;

  const std::optional<std::filesystem::path>& folder() const { return folder_; }

 private:
  std::filesystem::path entry(const std::string& key) const;
  std::optional<std::filesystem::path> folder_;
};

}  // namespace voxr
