#include "voxelize/grid_params.h"

#include <algorithm>
#include <array>

namespace voxr {

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
