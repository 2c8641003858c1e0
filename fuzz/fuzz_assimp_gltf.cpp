// libFuzzer target: glTF 2.0 (JSON, buffers embedded as base64 data URIs) through read_with_assimp, then
// triangulate (assimp_target.h).
#include "assimp_target.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  return voxr::fuzz::run_assimp(data, size, ".gltf");
}
