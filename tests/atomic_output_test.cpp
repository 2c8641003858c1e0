// Outputs appear only when complete (io/atomic_file.h): the helper itself, and the voxr executable when a
// write fails after output has started.
//
// Write failures are real ones, not injected: RLIMIT_FSIZE makes write(2) fail with EFBIG ("File too
// large") once a file would grow past the limit, for root too (permission tricks are unreliable as root),
// with SIGXFSZ ignored so the process sees the error instead of being killed. It is the same path a full
// disk (ENOSPC) takes through the writer.
#include <gtest/gtest.h>

#include <fcntl.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <csignal>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "cli_support.h"
#include "io/atomic_file.h"
#include "test_support.h"
#include "util/error.h"

namespace voxr {
namespace {

namespace fs = std::filesystem;
using test::TempDir;

using test::listing;
using test::slurp;

// Lowers this process's file size limit to `bytes` (SIGXFSZ ignored) until destroyed.
class FileSizeLimit {
 public:
  explicit FileSizeLimit(rlim_t bytes) {
    getrlimit(RLIMIT_FSIZE, &saved_);
    old_handler_ = std::signal(SIGXFSZ, SIG_IGN);
    rlimit limit = saved_;
    limit.rlim_cur = bytes;
    EXPECT_EQ(setrlimit(RLIMIT_FSIZE, &limit), 0);
  }
  ~FileSizeLimit() {
    setrlimit(RLIMIT_FSIZE, &saved_);
    std::signal(SIGXFSZ, old_handler_);
  }

 private:
  rlimit saved_{};
  void (*old_handler_)(int) = nullptr;
};

TEST(AtomicFile, CommitMovesTheCompleteFileIntoPlace) {
  TempDir dir;
  const fs::path out = dir.path() / "out.bin";
  AtomicFile file(out);
  file.write("hello ");
  file.write_pod(uint32_t(0x0a646c72));  // "rld\n" little-endian
  EXPECT_FALSE(fs::exists(out)) << "visible before commit";
  EXPECT_EQ(file.temp_path().parent_path(), out.parent_path()) << "rename must stay in the folder";
  EXPECT_EQ(file.temp_path().filename().string().rfind(".out.bin.tmp-", 0), 0u) << file.temp_path();
  EXPECT_TRUE(fs::exists(file.temp_path()));
  file.commit();
  EXPECT_TRUE(file.committed());
  EXPECT_EQ(slurp(out), "hello rld\n");
  EXPECT_EQ(listing(dir.path()), std::set<std::string>{"out.bin"});
}

TEST(AtomicFile, CommitReplacesAnExistingFile) {
  TempDir dir;
  const fs::path out = dir.write("report.json", "old");
  write_file_atomically(out, "new");
  EXPECT_EQ(slurp(out), "new");
  EXPECT_EQ(listing(dir.path()), std::set<std::string>{"report.json"});
}

TEST(AtomicFile, UncommittedLeavesNothing) {
  TempDir dir;
  {
    AtomicFile file(dir.path() / "out.bin");
    file.write("partial");
    file.close();  // even a closed, complete temporary goes without commit()
  }
  EXPECT_TRUE(listing(dir.path()).empty());
}

TEST(AtomicFile, ExceptionKeepsTheExistingFileAndLeavesNoTemporary) {
  TempDir dir;
  const fs::path out = dir.write("out.vti", "old contents");
  EXPECT_THROW(
      {
        AtomicFile file(out);
        file.write(std::string(100000, 'x'));
        throw std::runtime_error("the grid could not be read back");
      },
      std::runtime_error);
  EXPECT_EQ(slurp(out), "old contents");
  EXPECT_EQ(listing(dir.path()), std::set<std::string>{"out.vti"});
}

TEST(AtomicFile, WriteFailureNamesTheFileKeepsTheExistingOneAndLeavesNoTemporary) {
  TempDir dir;
  const fs::path out = dir.write("out.nrrd", "old contents");
  std::string message;
  {
    const FileSizeLimit limit(4096);
    try {
      AtomicFile file(out);
      for (int i = 0; i < 2048; ++i) file.write(std::string(1024, 'x'));  // past the 1 MiB buffer
      file.commit();
    } catch (const Error& e) {
      message = e.what();
    }
  }
  EXPECT_NE(message.find(out.string()), std::string::npos) << message;
  EXPECT_NE(message.find("File too large"), std::string::npos) << message;
  EXPECT_EQ(slurp(out), "old contents");
  EXPECT_EQ(listing(dir.path()), std::set<std::string>{"out.nrrd"});
}

TEST(AtomicFile, FailureWhileFlushingIsAnError) {
  // Less than a block: buffered, so the error only shows when close() flushes.
  TempDir dir;
  const fs::path out = dir.path() / "small.csv";
  std::string message;
  {
    const FileSizeLimit limit(1024);
    AtomicFile file(out);
    file.write(std::string(2000, 'x'));
    try {
      file.commit();
    } catch (const Error& e) {
      message = e.what();
    }
  }
  EXPECT_NE(message.find(out.string()), std::string::npos) << message;
  EXPECT_FALSE(fs::exists(out));
  EXPECT_TRUE(listing(dir.path()).empty());
}

// Issue 20, kind 9: an existing read-only output was silently replaced through the rename (and lost its
// mode). It is refused, untouched; a writable file replaced keeps its permissions.
TEST(AtomicFile, ReadOnlyOutputIsRefusedAndLeftUntouched) {
  TempDir dir;
  const fs::path out = dir.write("locked.nrrd", "old");
  fs::permissions(out, fs::perms::owner_read | fs::perms::group_read | fs::perms::others_read);
  try {
    write_file_atomically(out, "new");
    FAIL() << "a read-only file was replaced";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()), out.string() + ": the file exists and is read-only (left untouched)");
  }
  EXPECT_EQ(slurp(out), "old");
  EXPECT_EQ(fs::status(out).permissions(),
            fs::perms::owner_read | fs::perms::group_read | fs::perms::others_read);
  EXPECT_EQ(listing(dir.path()), std::set<std::string>{"locked.nrrd"});

  const fs::path shared = dir.write("shared.json", "old");
  const fs::perms mode = fs::perms::owner_read | fs::perms::owner_write | fs::perms::group_read;
  fs::permissions(shared, mode);
  write_file_atomically(shared, "new");
  EXPECT_EQ(slurp(shared), "new");
  EXPECT_EQ(fs::status(shared).permissions(), mode);
}

TEST(AtomicFile, MissingFolderIsAnErrorNamingTheFile) {
  TempDir dir;
  const fs::path out = dir.path() / "no-such-folder" / "out.vti";
  try {
    AtomicFile file(out);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(out.string()), std::string::npos) << e.what();
  }
  EXPECT_TRUE(listing(dir.path()).empty());
}

TEST(AtomicFile, ConcurrentFilesForOneNameDoNotShareATemporary) {
  TempDir dir;
  const fs::path out = dir.path() / "out.bin";
  AtomicFile a(out), b(out);
  EXPECT_NE(a.temp_path(), b.temp_path());
  a.write("a");
  b.write("b");
  a.commit();
  b.commit();
  EXPECT_EQ(slurp(out), "b");
  EXPECT_EQ(listing(dir.path()), std::set<std::string>{"out.bin"});
}

// ---- The voxr executable -------------------------------------------------------------------------------

struct Run {
  int code = -1;
  std::string err;
};

// Runs voxr with `args`, stdout discarded, stderr captured; with `fsize_limit` > 0 the file size limit is
// set (and SIGXFSZ ignored) in the child only.
Run run_voxr(const std::vector<std::string>& args, rlim_t fsize_limit = 0) {
  const TempDir logs;
  const fs::path err = logs.path() / "stderr.txt";
  std::vector<std::string> argv = {VOXR_CLI_PATH};
  argv.insert(argv.end(), args.begin(), args.end());
  std::vector<char*> pointers;
  for (std::string& a : argv) pointers.push_back(a.data());
  pointers.push_back(nullptr);
  const pid_t pid = fork();
  if (pid == 0) {
    const int null_fd = open("/dev/null", O_WRONLY);
    const int err_fd = open(err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (null_fd < 0 || err_fd < 0 || dup2(null_fd, 1) < 0 || dup2(err_fd, 2) < 0) _exit(126);
    if (fsize_limit > 0) {
      signal(SIGXFSZ, SIG_IGN);  // an ignored signal stays ignored across exec
      rlimit limit{};
      getrlimit(RLIMIT_FSIZE, &limit);
      limit.rlim_cur = fsize_limit;
      if (setrlimit(RLIMIT_FSIZE, &limit) != 0) _exit(126);
    }
    execv(pointers[0], pointers.data());
    _exit(127);
  }
  int status = 0;
  EXPECT_EQ(waitpid(pid, &status, 0), pid);
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, slurp(err)};
}

const std::string kTetra = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";

void expect_failure_naming(const Run& r, const fs::path& file) {
  EXPECT_EQ(r.code, 1) << r.err;
  EXPECT_NE(r.err.find(file.string()), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("File too large"), std::string::npos) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
}

TEST(AtomicOutput, FailedVolumeWriteKeepsTheOldFileAndLeavesNoTemporary) {
  TempDir dir;
  const fs::path mesh = dir.write("tetra.obj", kTetra);
  const std::vector<std::string> grid = {"voxelize", mesh.string(), "--dims", "32,32,32", "-q"};
  auto with = [&](std::vector<std::string> extra) {
    std::vector<std::string> a = grid;
    a.insert(a.end(), extra.begin(), extra.end());
    return a;
  };
  // The same run without a limit first: the program caches are warm, so under the limit the only
  // files written are the outputs.
  ASSERT_EQ(run_voxr(with({"-o", (dir.path() / "warm.vti").string()})).code, 0);

  // .vti: 32^3 occupancy bytes do not fit in 16 KiB; the write fails part way through the file.
  const fs::path vti = dir.write("out.vti", "old volume");
  expect_failure_naming(run_voxr(with({"-o", vti.string()}), 16 << 10), vti);
  EXPECT_EQ(slurp(vti), "old volume");
  EXPECT_EQ(listing(dir.path()), (std::set<std::string>{"tetra.obj", "warm.vti", "out.vti"}));
}

TEST(AtomicOutput, FailedSideFileLeavesNoneOfTheSet) {
  TempDir dir;
  const fs::path mesh = dir.write("tetra.obj", kTetra);
  const std::vector<std::string> base = {"voxelize", mesh.string(), "--dims",    "32,32,32",
                                         "-q",       "--channels",  "occ,count", "-o"};
  auto with = [&](const fs::path& out) {
    std::vector<std::string> a = base;
    a.push_back(out.string());
    return a;
  };
  ASSERT_EQ(run_voxr(with(dir.path() / "warm.nrrd")).code, 0);
  ASSERT_TRUE(fs::exists(dir.path() / "warm.count.nrrd"));
  fs::remove(dir.path() / "warm.nrrd");
  fs::remove(dir.path() / "warm.count.nrrd");

  // 64 KiB: the occupancy file (32 KiB + header) is written and closed, the uint32 count file (128 KiB)
  // fails; neither may appear.
  const fs::path out = dir.path() / "out.nrrd";
  expect_failure_naming(run_voxr(with(out), 64 << 10), dir.path() / "out.count.nrrd");
  EXPECT_EQ(listing(dir.path()), std::set<std::string>{"tetra.obj"});
}

TEST(AtomicOutput, FailedReportKeepsTheOldReport) {
  TempDir dir;
  const fs::path mesh = dir.write("tetra.obj", kTetra);
  const fs::path report = dir.write("report.json", "{}");
  const std::vector<std::string> args = {"voxelize", mesh.string(), "--res", "8", "-q", "--report"};
  auto with = [&](const fs::path& out) {
    std::vector<std::string> a = args;
    a.push_back(out.string());
    return a;
  };
  ASSERT_EQ(run_voxr(with(dir.path() / "warm.json")).code, 0);
  ASSERT_GT(fs::file_size(dir.path() / "warm.json"), 512u);
  expect_failure_naming(run_voxr(with(report), 512), report);
  EXPECT_EQ(slurp(report), "{}");
  EXPECT_EQ(listing(dir.path()), (std::set<std::string>{"tetra.obj", "report.json", "warm.json"}));
}

}  // namespace
}  // namespace voxr
