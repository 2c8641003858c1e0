// libFuzzer target: read_stl (ASCII and binary), then triangulate (fuzz_target.h).
#include <vector>

#include "fuzz_target.h"
#include "mesh/mesh_readers.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string name = "fuzz.stl";
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  std::vector<std::string> notes;
  voxr::fuzz::run(name, [&] { return voxr::read_stl(name, bytes, notes); });
  for (const std::string& n : notes)
    if (n.rfind(name, 0) != 0 || n.find('\n') != std::string::npos) voxr::fuzz::broken("note not one line");
  return 0;
}
