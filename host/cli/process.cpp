#include "cli/process.h"

#include <spawn.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>

#include "util/error.h"

namespace voxr::cli {

std::filesystem::path executable_path() {
  std::error_code ec;
  const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", ec);
  return ec ? std::filesystem::path() : exe;
}

std::filesystem::path executable_folder() {
  return executable_path().parent_path();
}

int run_program(std::vector<std::string> argv, uint64_t* peak_rss_bytes) {
  std::vector<char*> pointers;
  for (std::string& a : argv) pointers.push_back(a.data());
  pointers.push_back(nullptr);
  std::fflush(stdout);
  pid_t pid = 0;
  if (posix_spawn(&pid, pointers[0], nullptr, nullptr, pointers.data(), environ) != 0)
    fail("cannot start {}", argv[0]);
  int status = 0;
  rusage usage{};
  while (wait4(pid, &status, 0, &usage) < 0 && errno == EINTR) {
  }
  if (peak_rss_bytes) *peak_rss_bytes = uint64_t(usage.ru_maxrss) * 1024;  // Linux: KiB
  return WIFEXITED(status) ? WEXITSTATUS(status) : 1;
}

void exec_program(const std::filesystem::path& program, int argc, char** argv) {
  std::string path = program.string();
  std::vector<char*> pointers{path.data()};
  for (int i = 1; i < argc; ++i) pointers.push_back(argv[i]);
  pointers.push_back(nullptr);
  std::fflush(stdout);
  execv(path.c_str(), pointers.data());
  fail("cannot start {} (build the voxr-render target beside voxr)", path);
}

}  // namespace voxr::cli
