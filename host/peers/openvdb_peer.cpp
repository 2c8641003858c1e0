#include "peers/openvdb_peer.h"

#include <openvdb/openvdb.h>
#include <openvdb/tools/MeshToVolume.h>

#include <bit>
#include <cmath>
#include <cstdio>
#include <exception>

#include "util/clock.h"

extern "C" bool voxr_openvdb_mesh_to_volume(const voxr::TriangleSoup* soup, const voxr::GridSpec* grid,
                                            const float* m, voxr::VoxelGrid* out, double* ms, char* error,
                                            size_t error_size) {
  try {
    openvdb::initialize();
    // Mesh in grid units, so OpenVDB's index (i,j,k) sits at voxr's voxel centre (i+1/2, j+1/2, k+1/2).
    std::vector<openvdb::Vec3s> points;
    points.reserve(soup->positions.size());
    for (const glm::vec4& p : soup->positions) {
      openvdb::Vec3s q;
      for (int a = 0; a < 3; ++a)
        q[a] = m[4 * a] * p.x + m[4 * a + 1] * p.y + m[4 * a + 2] * p.z + m[4 * a + 3] - 0.5f;
      points.push_back(q);
    }
    std::vector<openvdb::Vec3I> triangles;
    triangles.reserve(soup->triangles.size());
    for (const glm::uvec4& t : soup->triangles) triangles.emplace_back(t.x, t.y, t.z);
    const std::vector<openvdb::Vec4I> quads;
    const openvdb::math::Transform::Ptr xform = openvdb::math::Transform::createLinearTransform(1.0);

    const auto start = voxr::Clock::now();
    const openvdb::FloatGrid::Ptr udf = openvdb::tools::meshToUnsignedDistanceField<openvdb::FloatGrid>(
        *xform, points, triangles, quads, 1.0f);
    *ms = voxr::ms_since(start);

    *out = voxr::VoxelGrid{};
    out->spec = *grid;
    out->occ.assign((grid->voxel_count() + 31) / 32, 0u);
    const float limit = 0.5f * std::sqrt(3.0f);
    for (auto it = udf->cbeginValueOn(); it; ++it) {
      if (*it > limit) continue;
      const openvdb::Coord c = it.getCoord();
      if (c.x() < 0 || c.y() < 0 || c.z() < 0 || c.x() >= int(grid->dims.x) || c.y() >= int(grid->dims.y) ||
          c.z() >= int(grid->dims.z))
        continue;
      const uint64_t linear = grid->linear_index(uint32_t(c.x()), uint32_t(c.y()), uint32_t(c.z()));
      out->occ[linear >> 5] |= 1u << (linear & 31);
    }
    for (uint32_t w : out->occ) out->voxels_set += uint64_t(std::popcount(w));
    return true;
  } catch (const std::exception& e) {
    std::snprintf(error, error_size, "%s", e.what());
    return false;
  }
}
