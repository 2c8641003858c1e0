#include "core/grid_spec.h"

#include <algorithm>
#include <cmath>

#include "util/error.h"

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

glm::dvec3 GridSpec::voxel_center_absolute(uint32_t i, uint32_t j, uint32_t k) const {
  return anchor + glm::dvec3(origin) + glm::dmat3(axes) * (glm::dvec3(i, j, k) + 0.5) * double(voxel_size);
}

namespace {

void check_dims(const glm::uvec3& dims) {
  for (int a = 0; a < 3; ++a)
    if (dims[a] == 0 || dims[a] > kMaxGridDim)
      fail("grid dimension {} along {} is out of range (1..{})", dims[a], "xyz"[a], kMaxGridDim);
}

}  // namespace

namespace {

// Distance of `x` (in voxels) from the nearest voxel face or voxel centre.
double tie_distance(double x) {
  const double r = x - 0.5 * std::floor(2.0 * x);  // x modulo half a voxel
  return std::min(r, 0.5 - r);
}

// Offset, in voxels, of the low face of bounds `extent` voxels long in an axis of `slack` + extent voxels:
// centred when both faces then keep 1/8 voxel from ties, else the offset nearest the centre whose faces
// keep the most (faces x and x + extent, taken modulo half a voxel, straddle the tie point symmetrically).
double low_face_offset(double extent, double slack) {
  const double centred = 0.5 * slack;
  if (std::min(tie_distance(centred), tie_distance(centred + extent)) >= 0.125) return centred;
  const double g = std::fmod(extent, 0.5);
  const double best = g >= 0.25 ? 0.5 - 0.5 * g : 0.25 - 0.5 * g;  // modulo 0.5
  double offset = centred;
  for (double x = best; x <= slack; x += 0.5)
    if (offset == centred || std::abs(x - centred) < std::abs(offset - centred)) offset = x;
  return offset;
}

}  // namespace

GridSpec fit_grid(const Bounds& scene_bounds, const GridRequest& request, const glm::dvec3& anchor) {
  if (!request.dims && (request.resolution == 0 || request.resolution > kMaxGridDim))
    fail("--res {} is out of range (1..{})", request.resolution, kMaxGridDim);
  if (request.dims) check_dims(*request.dims);

  const bool exact_bounds = request.bounds.has_value();
  Bounds b = scene_bounds;
  if (exact_bounds) {
    for (int a = 0; a < 3; ++a)
      if (!std::isfinite(request.bounds->lo[a]) || !std::isfinite(request.bounds->hi[a]))
        fail("the grid bounds are not finite");
    b.lo = glm::vec3(request.bounds->lo - anchor);
    b.hi = glm::vec3(request.bounds->hi - anchor);
  }
  if (b.empty()) fail("the grid bounds are empty");
  for (int a = 0; a < 3; ++a)
    if (!std::isfinite(b.lo[a]) || !std::isfinite(b.hi[a])) fail("the grid bounds are not finite");
  const glm::vec3 extent = b.size();
  const float longest = std::max({extent.x, extent.y, extent.z});
  if (!(longest > 0.0f)) fail("the scene bounds are a single point; give --bounds explicitly");

  const float margin = exact_bounds ? 0.0f : request.margin_voxels;
  GridSpec g;
  g.anchor = anchor;
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
  if (exact_bounds) {
    g.origin = b.lo;  // exact bounds start at their corner
  } else {
    for (int a = 0; a < 3; ++a) {
      const double cells = double(extent[a]) / g.voxel_size;
      const double slack = std::max(0.0, double(g.dims[a]) - cells);
      g.origin[a] = float(double(b.lo[a]) - low_face_offset(cells, slack) * g.voxel_size);
    }
  }
  return g;
}

}  // namespace voxr
