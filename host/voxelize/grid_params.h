// The parameter block every voxelization kernel takes (kernels/voxr_layout.h VoxGridParams), filled in one
// place.
#pragma once

#include <cstdint>

#include "core/grid_spec.h"
#include "voxr_layout.h"

namespace voxr {

// `margin`: conservative widening of voxel boxes (snap_margin), 0 for the centre rule; `channels`: the
// ChannelSet bits an attribute pass accumulates.
VoxGridParams make_grid_params(const GridSpec& grid, uint32_t triangle_count, uint32_t margin,
                               uint32_t rows_per_copy = 4, uint32_t channels = 0);

}  // namespace voxr
