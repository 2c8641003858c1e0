// The OpenCL runtime every benchmark of voxr_bench shares (one context and queue per process), on
// $VOXR_DEVICE or the default device, created on first use.
#pragma once

#include "cl/cl_runtime.h"

namespace voxr {

inline ClRuntime& bench_runtime() {
  static ClRuntime rt("");
  return rt;
}

}  // namespace voxr
