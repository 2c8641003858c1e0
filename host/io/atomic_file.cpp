#include "io/atomic_file.h"

#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>

#include <fmt/format.h>

#include "util/error.h"

namespace voxr {

namespace fs = std::filesystem;

void check_output_path(const fs::path& out) {
  if (out.filename().empty()) fail("{}: the output path names a folder, not a file", out.string());
  const fs::path folder = out.parent_path();
  std::error_code ec;
  if (!folder.empty() && !fs::is_directory(folder, ec))
    fail("{}: folder '{}' does not exist", out.string(), folder.string());
  if (fs::is_directory(out, ec)) fail("{}: is a folder", out.string());
  // An existing file nobody may write (no write bit; root ignores the bits, so they are read here, not
  // asked of access()) or this user may not: refused, not replaced through the rename.
  struct stat st;
  if (::stat(out.c_str(), &st) == 0 &&
      ((st.st_mode & (S_IWUSR | S_IWGRP | S_IWOTH)) == 0 || ::access(out.c_str(), W_OK) != 0))
    fail("{}: the file exists and is read-only (left untouched)", out.string());
}

AtomicFile::AtomicFile(fs::path path) : path_(std::move(path)) {
  check_output_path(path_);
  static std::atomic<uint64_t> counter{0};
  // "x": never reuse a temporary left behind by a crashed process that had the same pid.
  do {
    temp_ =
        path_.parent_path() / fmt::format(".{}.tmp-{}-{}", path_.filename().string(), ::getpid(), counter++);
    errno = 0;
    file_ = std::fopen(temp_.c_str(), "wbx");
  } while (!file_ && errno == EEXIST);
  if (!file_) fail_io("cannot create the file", errno);
  std::setvbuf(file_, nullptr, _IOFBF, size_t(1) << 20);
}

AtomicFile::~AtomicFile() {
  if (file_) std::fclose(file_);
  if (!committed_ && !temp_.empty()) {
    std::error_code ec;
    fs::remove(temp_, ec);
  }
}

void AtomicFile::fail_io(std::string_view what, int err) const {
  fail("{}: {}: {}", path_.string(), what, err ? std::strerror(err) : "unknown error");
}

void AtomicFile::write(const void* data, size_t bytes) {
  if (!file_) fail("{}: write after the file was closed", path_.string());
  errno = 0;
  if (bytes != 0 && std::fwrite(data, 1, bytes, file_) != bytes) fail_io("write failed", errno);
}

void AtomicFile::close() {
  if (closed_) return;
  closed_ = true;
  errno = 0;
  const bool flushed = std::fflush(file_) == 0 && !std::ferror(file_);
  const int flush_errno = errno;
  errno = 0;
  const bool closed = std::fclose(file_) == 0;
  const int close_errno = errno;
  file_ = nullptr;
  if (!flushed) fail_io("write failed", flush_errno);
  if (!closed) fail_io("write failed", close_errno);
}

void AtomicFile::commit() {
  close();
  if (committed_) return;
  // A file replaced keeps its permissions (the temporary was created with the umask's).
  struct stat st;
  if (::stat(path_.c_str(), &st) == 0) ::chmod(temp_.c_str(), st.st_mode & 07777);
  errno = 0;
  if (std::rename(temp_.c_str(), path_.c_str()) != 0)
    fail_io("cannot move the finished file into place", errno);
  committed_ = true;
}

void write_file_atomically(const fs::path& path, std::string_view text) {
  AtomicFile file(path);
  file.write(text);
  file.commit();
}

}  // namespace voxr
