// Small helpers the subcommands share: finding the executable, starting a program and waiting for it.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace voxr::cli {

// The running executable, and its folder (voxr-view and the OpenVDB plugin live beside it); empty if unknown.
std::filesystem::path executable_path();
std::filesystem::path executable_folder();

// Runs `argv` (argv[0] = the program's path) with this process's environment, waits for it and returns its
// exit status (1 when it did not exit normally); `peak_rss_bytes` (optional) receives its peak resident
// memory. Throws voxr::Error when it cannot be started.
int run_program(std::vector<std::string> argv, uint64_t* peak_rss_bytes = nullptr);

// Replaces this process with `program` given this process's arguments (argv[0] becomes `program`). Returns
// only by throwing voxr::Error when `program` cannot be started.
[[noreturn]] void exec_program(const std::filesystem::path& program, int argc, char** argv);

}  // namespace voxr::cli
