// Running the voxr executable from tests: its exit code, stdout and stderr, and files in a scratch folder.
#pragma once

#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace voxr::test {

struct CliResult {
  int code = -1;  // exit status; -1 when voxr did not exit normally
  std::string out, err;
};

// One folder per test process: ctest runs tests in parallel processes that must not share files.
std::filesystem::path scratch();

// A whole file's bytes; empty when it cannot be read.
std::string slurp(const std::filesystem::path& p);

// Runs `voxr ARGS` through the shell with stdin from /dev/null and the environment assignments `env`
// ("A=1 B=2") prefixed. Arguments are the test's own: no quoting is done.
CliResult run_voxr(const std::string& args, const std::string& env = "");

// Writes `content` to scratch()/name and returns the path.
std::filesystem::path write_scratch_file(const std::string& name, const std::string& content);

// A CSV file without quoted commas as one column-name -> cell map per row (EXPECTs every row to have the
// header's number of cells).
std::vector<std::map<std::string, std::string>> read_csv(const std::filesystem::path& path);

// Number of '\n' in `text`.
int count_lines(const std::string& text);

}  // namespace voxr::test
