// How far a surface voxelization lies from its triangles, in world units relative to the scene's size, so
// that errors at different resolutions and of different methods compare (speed against accuracy, and
// `voxr voxelize --error-target`). The two-sided mean surface distance (Chamfer distance) between the set
// voxels and the surface:
//   mesh_to_voxels  mean, over points sampled uniformly by area on the triangles, of the distance from the
//                   point to the nearest set voxel's closed box (0 inside one): holes raise it;
//   voxels_to_mesh  mean, over the set voxels (all, or a uniform sample of `samples`), of the distance from
//                   the voxel's centre to the nearest triangle: thickness and stray voxels raise it.
// Both divided by the longest side of the grid's bounds. A surface sample with no set voxel within
// kSearchVoxels voxels counts kSearchVoxels voxels (a hole that large is a failure, not a distance).
#pragma once

#include <cstdint>

#include "core/grid_spec.h"
#include "core/triangle_soup.h"
#include "grid/voxel_grid.h"

namespace voxr {

struct VoxelSurfaceError {
  double mesh_to_voxels = 0.0;  // relative to the longest side of the grid's bounds
  double voxels_to_mesh = 0.0;  // the same
  double hole_share = 0.0;      // surface samples more than half a voxel diagonal from every set voxel
  uint64_t surface_samples = 0, voxel_samples = 0;
  double chamfer() const { return mesh_to_voxels + voxels_to_mesh; }
};

inline constexpr int kSearchVoxels = 4;

// `grid` holds the occupancy of `soup` voxelized on `spec` (any method, any channels: occupancy is what is
// read). Deterministic for a given `seed`. Throws voxr::Error for an empty soup.
VoxelSurfaceError voxel_surface_error(const VoxelGrid& grid, const GridSpec& spec, const TriangleSoup& soup,
                                      uint32_t samples = 100000, uint64_t seed = 1);

}  // namespace voxr
