// The two rasterization rules of the slice voxelizer (see kernels/vox_raster.cl for the exact predicates).
#pragma once

#include <string>
#include <string_view>

#include "voxr_layout.h"

namespace voxr {

enum class RasterMode { kConservative = VOXR_MODE_CONSERVATIVE, kCenter = VOXR_MODE_CENTER };

RasterMode parse_raster_mode(std::string_view name);  // "conservative" | "center"; throws voxr::Error
const char* raster_mode_name(RasterMode mode);

}  // namespace voxr
