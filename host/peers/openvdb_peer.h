// OpenVDB's mesh-to-volume as a CPU peer for the benchmarks. It builds a narrow-band unsigned distance field
// of one voxel around the triangles on the same voxel centres as voxr's grid (index (i,j,k) = voxr voxel
// (i,j,k)); voxels whose centre lies within half a voxel diagonal of the surface are reported as set, a
// superset of the triangle/box overlap set.
//
// The peer is a plugin (libvoxr_openvdb_peer.so, built beside the voxr executable when libopenvdb-dev is
// installed) loaded only when a benchmark asks for it: linking OpenVDB and its dependencies into voxr itself
// cost every `voxr` process about 40 ms of dynamic loading.
#pragma once

#include <cstddef>

#include "core/grid_spec.h"
#include "core/triangle_soup.h"
#include "grid/voxel_grid.h"

extern "C" {
// The plugin's entry point: voxelizes `soup` on `grid` (world_to_grid = grid.world_to_grid()) into `out`
// (occupancy) and times OpenVDB's conversion with the host clock (it runs multi-threaded through TBB) into
// *ms; the copy into voxr's grid is not timed. Returns false with a message in `error` on failure.
bool voxr_openvdb_mesh_to_volume(const voxr::TriangleSoup* soup, const voxr::GridSpec* grid,
                                 const float* world_to_grid, voxr::VoxelGrid* out, double* ms, char* error,
                                 size_t error_size);
}
