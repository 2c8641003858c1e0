// The slicing of a slicemap (Eisemann & Decoret 2006): uniform (bit b = voxel slab b) or local (each
// column's bits spread over its own near/far depth range). See host/voxelize/slicemap_voxelizer.h.
#pragma once

#include <string_view>

namespace voxr {

enum class SlicemapSlicing { kUniform, kLocal };

const char* slicemap_slicing_name(SlicemapSlicing slicing);     // "uniform" | "local"
SlicemapSlicing parse_slicemap_slicing(std::string_view name);  // throws voxr::Error naming a bad value

}  // namespace voxr
