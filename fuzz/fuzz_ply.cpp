// libFuzzer target: read_ply, then triangulate (fuzz_target.h).
#include "fuzz_target.h"
#include "mesh/mesh_readers.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string name = "fuzz.ply";
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  return voxr::fuzz::run(name, [&] { return voxr::read_ply(name, bytes); });
}
