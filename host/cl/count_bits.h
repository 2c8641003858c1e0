// The number of set bits in a device array of 32-bit words (kernels/count_bits.cl): the voxel count of a
// dense bit channel without reading it back.
#pragma once

#include <cstdint>
#include <vector>

#include "cl/cl_runtime.h"

namespace voxr {

// The programs count_bits builds, for building them ahead of timed work.
std::vector<ProgramSpec> count_bits_programs();

// Blocks until the count is known. Needs cl_khr_int64_base_atomics (PoCL and NVIDIA have it).
uint64_t count_bits(ClRuntime& cl, const cl::Buffer& words, uint64_t n, const std::string& name);

}  // namespace voxr
