#include "voxelize/grid_params.h"

#include <algorithm>
#include <array>

namespace voxr {

void expect_no_oversized(ClRuntime& cl, const cl::Buffer& too_large, const std::string& name) {
  auto check = [](uint64_t oversized) {
    if (oversized)
      throw InternalError(
          fmt::format("{} triangles exceed {} voxels; split_oversized_triangles must run first", oversized,
                      VOXR_MAX_TRIANGLE_EXTENT));
    return true;
  };
  if (cl.counts_deferred()) {
    cl.read_count_later(too_large, 4, "readback " + name, check);
    return;
  }
  cl_uint oversized = 0;
  cl.download(too_large, &oversized, 4, "readback " + name);
  check(oversized);
}

VoxGridParams make_grid_params(const GridSpec& grid, uint32_t triangle_count, uint32_t margin,
                               uint32_t rows_per_copy, uint32_t channels) {
  VoxGridParams params{};
  const std::array<float, 12> m = grid.world_to_grid();
  std::copy(m.begin(), m.end(), params.world_to_grid);
  for (int a = 0; a < 3; ++a) params.dims[a] = grid.dims[a];
  params.rows_per_copy = rows_per_copy;
  params.triangle_count = triangle_count;
  params.margin = margin;
  params.channels = channels;
  return params;
}

}  // namespace voxr
