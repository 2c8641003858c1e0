// CPU references for solid voxelization, on the same snapped vertices as the kernels (oversized triangles
// split as the kernels' input is). Inside sets are dense bit vectors in VoxelGrid::occ's layout.
//   reference_inside_exact    exact inside test of every voxel centre: parity of the crossings of the ray
//                             from the centre along +z, in 128-bit integers, one column at a time over the
//                             triangles whose projection may hold it. Independent of the kernels (which
//                             scatter per triangle and count crossings below the centre); on a closed mesh
//                             the two parities agree (see solid_fill.h).
//   reference_inside_winding  generalized winding number (Jacobson et al. 2013: sum of the triangles' solid
//                             angles / 4 pi, double precision), inside where |w| > 0.5: the reference for
//                             open meshes and meshes with holes.
//   reference_solid           each mode's own output, written without the kernels' data layouts or loop
//                             structure, for exact kernel-vs-reference comparison.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "core/grid_spec.h"
#include "core/triangle_soup.h"
#include "grid/voxel_grid.h"
#include "voxelize/solid_mode.h"

namespace voxr {

std::vector<uint32_t> reference_inside_exact(const TriangleSoup& soup, const GridSpec& grid);
// Inside where |w| > threshold. Computed as the signed +z ray count of the mesh closed by a cone over its
// boundary edges, minus the cone's solid angles (exact up to the double rounding of those few angles).
std::vector<uint32_t> reference_inside_winding(const TriangleSoup& soup, const GridSpec& grid,
                                               double threshold = 0.5);
// The same by summing every triangle's solid angle at every centre (slow; cross-checks the one above).
std::vector<uint32_t> reference_inside_winding_direct(const TriangleSoup& soup, const GridSpec& grid,
                                                      double threshold = 0.5);

struct ReferenceSolid {
  std::vector<uint32_t> inside;
  uint64_t questionable_columns = 0;  // late
  uint64_t repair_iterations = 0;     // late: rounds that resolved a column
};
// For kFlood the surface is reference_voxelize(..., kConservative, ...).
ReferenceSolid reference_solid(const TriangleSoup& soup, const GridSpec& grid, SolidMode mode);

// A solid result against reference bits: missing = inside in the reference only, extra = in the result only.
struct SolidError {
  uint64_t missing = 0;
  uint64_t extra = 0;
  uint64_t total() const { return missing + extra; }
};
SolidError compare_inside(const VoxelGrid& grid, std::span<const uint32_t> reference_bits);
// Counting only voxels outside `shell` (say the conservative surface's occ): the errors that a boundary rule
// off by part of a voxel does not explain — leaks along columns, lost interiors.
SolidError compare_inside(const VoxelGrid& grid, std::span<const uint32_t> reference_bits,
                          std::span<const uint32_t> shell);
// `shell` empty: every voxel counts.
SolidError compare_bits(std::span<const uint32_t> result, std::span<const uint32_t> reference_bits,
                        std::span<const uint32_t> shell = {});

uint64_t count_bits(std::span<const uint32_t> bits);

}  // namespace voxr
