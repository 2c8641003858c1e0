// Output files that appear only once they are complete. Every result voxr writes (volumes and their side
// files, --report JSON, bench CSV/Markdown) goes through AtomicFile: the bytes go to a hidden temporary in
// the destination folder (".NAME.tmp-PID-N", so the final rename stays on one file system and is atomic),
// are flushed and checked, and only then renamed over NAME. On any failure, or an exception that unwinds
// past an uncommitted file, the temporary is removed and NAME is left as it was (a file already there
// survives unchanged).
#pragma once

#include <cstdio>
#include <filesystem>
#include <string_view>

namespace voxr {

// Throws voxr::Error naming `out` when it names a folder, its folder does not exist, it is a folder, or it is
// an existing file that is read-only (no write permission bit, or not writable by this user).
void check_output_path(const std::filesystem::path& out);

class AtomicFile {
 public:
  // Creates the temporary beside `path`. Throws voxr::Error naming `path` when check_output_path() refuses
  // it or the temporary cannot be created (e.g. a read-only folder).
  explicit AtomicFile(std::filesystem::path path);
  // Removes the temporary unless commit() succeeded; never throws.
  ~AtomicFile();
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;

  // Appends bytes (buffered). Throws voxr::Error naming path() and the reason (e.g. "No space left on
  // device", "File too large") when the write fails, or after close().
  void write(const void* data, size_t bytes);
  void write(std::string_view text) { write(text.data(), text.size()); }
  template <typename T>
  void write_pod(const T& value) {
    write(&value, sizeof(T));
  }

  // Flushes and closes the temporary, checking every step; throws voxr::Error naming path() on failure.
  // Writers producing several files close all of them before committing any, so a failure while writing
  // leaves no half-updated set behind. Idempotent.
  void close();
  // close(), then renames the temporary over path(). Throws voxr::Error naming path() on failure (the
  // temporary is then removed by the destructor and path() is untouched).
  void commit();

  const std::filesystem::path& path() const { return path_; }
  // Where the bytes go until commit() (tests check that it disappears).
  const std::filesystem::path& temp_path() const { return temp_; }
  bool committed() const { return committed_; }

 private:
  [[noreturn]] void fail_io(std::string_view what, int err) const;

  std::filesystem::path path_;
  std::filesystem::path temp_;
  std::FILE* file_ = nullptr;
  bool closed_ = false;
  bool committed_ = false;
};

// Writes `text` to `path` through an AtomicFile. Throws voxr::Error naming `path` on any failure.
void write_file_atomically(const std::filesystem::path& path, std::string_view text);

}  // namespace voxr
