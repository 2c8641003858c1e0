#include "cli_support.h"

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cstdlib>
#include <fstream>
#include <sstream>

namespace voxr::test {

namespace fs = std::filesystem;

fs::path scratch() {
  const fs::path dir = fs::path(testing::TempDir()) / ("voxr_cli_test_" + std::to_string(getpid()));
  fs::create_directories(dir);
  return dir;
}

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

CliResult run_voxr(const std::string& args, const std::string& env) {
  // Output files of their own, so that tests running voxr from several threads do not share them.
  static std::atomic<int> counter{0};
  const std::string n = std::to_string(counter++);
  const fs::path out = scratch() / ("stdout" + n + ".txt"), err = scratch() / ("stderr" + n + ".txt");
  const std::string cmd = env + " " + std::string(VOXR_CLI_PATH) + " " + args + " >" + out.string() + " 2>" +
                          err.string() + " </dev/null";
  const int status = std::system(cmd.c_str());
  CliResult r{WIFEXITED(status) ? WEXITSTATUS(status) : -1, slurp(out), slurp(err)};
  std::error_code ec;
  fs::remove(out, ec);
  fs::remove(err, ec);
  return r;
}

fs::path write_scratch_file(const std::string& name, const std::string& content) {
  const fs::path p = scratch() / name;
  std::ofstream(p, std::ios::binary) << content;
  return p;
}

int count_lines(const std::string& text) {
  return int(std::count(text.begin(), text.end(), '\n'));
}

namespace {

std::vector<std::string> split(const std::string& line, char sep) {
  std::vector<std::string> cells;
  std::stringstream s(line);
  std::string cell;
  while (std::getline(s, cell, sep)) cells.push_back(cell);
  if (!line.empty() && line.back() == sep) cells.push_back("");
  return cells;
}

}  // namespace

std::vector<std::map<std::string, std::string>> read_csv(const fs::path& path) {
  std::stringstream text(slurp(path));
  std::string line;
  std::getline(text, line);
  const std::vector<std::string> header = split(line, ',');
  std::vector<std::map<std::string, std::string>> rows;
  while (std::getline(text, line)) {
    const std::vector<std::string> cells = split(line, ',');
    EXPECT_EQ(cells.size(), header.size()) << line;
    std::map<std::string, std::string> row;
    for (size_t i = 0; i < header.size() && i < cells.size(); ++i) row[header[i]] = cells[i];
    rows.push_back(row);
  }
  return rows;
}

}  // namespace voxr::test
