// libFuzzer target: binary glTF (.glb) through read_with_assimp, then triangulate (assimp_target.h).
#include "assimp_target.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  return voxr::fuzz::run_assimp(data, size, ".glb");
}
