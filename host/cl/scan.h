// Exclusive prefix sum of any length on the device (kernels/scan.cl): tiles, recursive tile totals, add.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "cl/cl_runtime.h"

namespace voxr {

enum class ScanKind {
  kUintToUlong,   // uint counts -> ulong offsets (copy offsets)
  kRankedWords,   // uint occupancy words -> ulong (rank of the word's first set bit << 32) | word
  kUlongToUlong,  // ulong -> ulong (the recursion over tile totals)
};

// The programs exclusive_scan builds (every kind), for building them ahead of timed work.
std::vector<ProgramSpec> scan_programs();

// Scans `n` elements of `in` into `out` and writes the grand total (a ulong, exact in 64 bits even where
// `out` holds 32-bit values) to `total` on the device, without waiting.
void exclusive_scan(ClRuntime& cl, ScanKind kind, const cl::Buffer& in, cl::Buffer& out, uint64_t n,
                    cl::Buffer& total, const std::string& name);

// The same, returning the grand total: blocks until it is known.
uint64_t exclusive_scan(ClRuntime& cl, ScanKind kind, const cl::Buffer& in, cl::Buffer& out, uint64_t n,
                        const std::string& name);

}  // namespace voxr
