// OpenVDB's mesh-to-volume as a CPU peer for the benchmarks (built only when libopenvdb-dev is present).
// It builds a narrow-band unsigned distance field of one voxel around the triangles on the same voxel
// centres as voxr's grid (index (i,j,k) = voxr voxel (i,j,k)); voxels whose centre lies within half a
// voxel diagonal of the surface are reported as set, a superset of the triangle/box overlap set.
#pragma once

#include "core/grid_spec.h"
#include "core/triangle_soup.h"
#include "grid/voxel_grid.h"
#include "voxelize/voxelizer.h"

namespace voxr {

// Times the conversion with the host clock (OpenVDB runs multi-threaded on the CPU through TBB) into
// stats->kernels_ms; the copy into voxr's grid is not timed.
VoxelGrid openvdb_mesh_to_volume(const TriangleSoup& soup, const GridSpec& grid, VoxelizeStats* stats);

}  // namespace voxr
