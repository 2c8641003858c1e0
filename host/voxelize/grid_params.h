// The parameter block every voxelization kernel takes (kernels/voxr_layout.h VoxGridParams), filled in one
// place.
#pragma once

#include <cstdint>
#include <string>

#include "cl/cl_runtime.h"
#include "core/grid_spec.h"
#include "voxr_layout.h"

namespace voxr {

// The setup kernels count triangles longer than VOXR_MAX_TRIANGLE_EXTENT into `too_large` (4 bytes); the
// host splits such triangles first (triangle_splitter.h), so a count above zero is a programming error:
// reads it back and throws voxr::InternalError naming the count (with deferred counts, from the caller's
// ClRuntime::settle_counts after its next wait).
void expect_no_oversized(ClRuntime& cl, const cl::Buffer& too_large, const std::string& name);

// `margin`: conservative widening of voxel boxes (snap_margin), 0 for the centre rule; `channels`: the
// ChannelSet bits an attribute pass accumulates.
VoxGridParams make_grid_params(const GridSpec& grid, uint32_t triangle_count, uint32_t margin,
                               uint32_t rows_per_copy = 4, uint32_t channels = 0);

}  // namespace voxr
