// Accuracy of a surface voxelization, one definition for every method (DESIGN.md, Metrics):
//  - true/false positives and negatives against the exact triangle/box overlap set of the input triangles
//    (reference_overlap.h);
//  - tunnels: axis-aligned rays through voxel-centre lines (along x, y and z) that cross the surface where
//    the voxel holding the crossing is not set — the ray slips through the voxelized surface there.
#pragma once

#include <cstdint>

#include "core/grid_spec.h"
#include "core/triangle_soup.h"
#include "grid/voxel_grid.h"

namespace voxr {

struct SurfaceAccuracy {
  uint64_t exact_voxels = 0;
  uint64_t true_positives = 0;
  uint64_t false_positives = 0;
  uint64_t false_negatives = 0;
  uint64_t crossings = 0;  // ray/surface crossings along the three axes
  uint64_t tunnels = 0;    // crossings whose voxel is empty
  double false_negative_rate() const {
    return exact_voxels ? double(false_negatives) / double(exact_voxels) : 0.0;
  }
  double tunnel_rate() const { return crossings ? double(tunnels) / double(crossings) : 0.0; }
};

// `exact` must be reference_overlap(soup, grid) on the same grid as `result`.
SurfaceAccuracy measure_surface_accuracy(const VoxelGrid& result, const VoxelGrid& exact,
                                         const TriangleSoup& soup);

// Crossings of the voxel-centre lines along each axis with the soup, and how many land in empty voxels.
void count_tunnels(const VoxelGrid& result, const TriangleSoup& soup, uint64_t* crossings, uint64_t* tunnels);

}  // namespace voxr
