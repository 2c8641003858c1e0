#include "core/grid_spec.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"

namespace voxr {

std::array<float, 12> GridSpec::world_to_grid() const {
  // grid = axes^T (world - origin) / h; rows of axes^T are the columns of axes.
  const float s = 1.0f / voxel_size;
  std::array<float, 12> m{};
  for (int r = 0; r < 3; ++r) {
    const glm::vec3 axis = axes[r] * s;
    m[4 * r + 0] = axis.x;
    m[4 * r + 1] = axis.y;
    m[4 * r + 2] = axis.z;
    m[4 * r + 3] = -glm::dot(axis, origin);
  }
  return m;
}

glm::vec3 GridSpec::to_grid(const glm::vec3& world) const {
  return glm::transpose(axes) * (world - origin) / voxel_size;
}

glm::vec3 GridSpec::voxel_center_world(uint32_t i, uint32_t j, uint32_t k) const {
  return origin + axes * (glm::vec3(i, j, k) + 0.5f) * voxel_size;
}

namespace {

void check_dims(const glm::uvec3& dims) {
  for (int a = 0; a < 3; ++a)
    if (dims[a] == 0 || dims[a] > kMaxGridDim)
      fail("grid dimension {} along {} is out of range (1..{})", dims[a], "xyz"[a], kMaxGridDim);
}

}  // namespace

GridSpec fit_grid(const Bounds& scene_bounds, const GridRequest& request) {
  if (!request.dims && (request.resolution == 0 || request.resolution > kMaxGridDim))
    fail("--res {} is out of range (1..{})", request.resolution, kMaxGridDim);
  if (request.dims) check_dims(*request.dims);

  const bool exact_bounds = request.bounds.has_value();
  const Bounds b = exact_bounds ? *request.bounds : scene_bounds;
  if (b.empty()) fail("the grid bounds are empty");
  for (int a = 0; a < 3; ++a)
    if (!std::isfinite(b.lo[a]) || !std::isfinite(b.hi[a])) fail("the grid bounds are not finite");
  const glm::vec3 extent = b.size();
  const float longest = std::max({extent.x, extent.y, extent.z});
  if (!(longest > 0.0f)) fail("the scene bounds are a single point; give --bounds explicitly");

  // Fitted bounds get `margin` voxels on each side so that surfaces on the bounds are not cut.
  const float margin = exact_bounds ? 0.0f : request.margin_voxels;
  GridSpec g;
  if (request.dims) {
    float h = 0.0f;
    for (int a = 0; a < 3; ++a) {
      const float usable = float((*request.dims)[a]) - 2.0f * margin;
      if (extent[a] > 0.0f) h = std::max(h, extent[a] / (usable > 0.0f ? usable : float((*request.dims)[a])));
    }
    g.voxel_size = h;
    g.dims = *request.dims;
  } else {
    const float n = float(request.resolution);
    const float usable = n - 2.0f * margin;
    g.voxel_size = longest / (usable >= 0.5f * n ? usable : n);
    for (int a = 0; a < 3; ++a) {
      const float cells = extent[a] / g.voxel_size + 2.0f * margin;
      g.dims[a] = std::clamp<uint32_t>(uint32_t(std::ceil(cells - 1e-3f)), 1u, request.resolution);
    }
  }
  if (!(g.voxel_size > 0.0f) || !std::isfinite(g.voxel_size)) fail("cannot fit a grid to the bounds");
  check_dims(g.dims);
  // Exact bounds start at their corner; fitted grids are centred on the scene.
  const glm::vec3 span = glm::vec3(g.dims) * g.voxel_size;
  g.origin = exact_bounds ? b.lo : 0.5f * (b.lo + b.hi) - 0.5f * span;
  return g;
}

}  // namespace voxr
