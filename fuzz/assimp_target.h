// Body of the Assimp targets: read_with_assimp takes a path, so each input is written to a file with the
// target's extension in a per-process temporary folder (removed at exit), then read and triangulated.
#pragma once

#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "fuzz_target.h"
#include "mesh/assimp_reader.h"

namespace voxr::fuzz {

inline int run_assimp(const uint8_t* data, size_t size, const char* extension) {
  namespace fs = std::filesystem;
  static const fs::path dir = [] {
    const fs::path d = fs::temp_directory_path() / ("voxr-fuzz-" + std::to_string(::getpid()));
    fs::create_directories(d);
    std::atexit([] {
      std::error_code ec;
      fs::remove_all(fs::temp_directory_path() / ("voxr-fuzz-" + std::to_string(::getpid())), ec);
    });
    return d;
  }();
  const fs::path file = dir / (std::string("input") + extension);
  {
    std::ofstream out(file, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data), std::streamsize(size));
  }
  return run(file.string(), [&] { return read_with_assimp(file); });
}

}  // namespace voxr::fuzz
