// voxr::version(): the project version CMake was configured with.
#include "voxr/voxr.h"

namespace voxr {

std::string version() {
  return VOXR_VERSION;
}

}  // namespace voxr
