// Solid voxelization: which voxel centres lie inside the mesh. The slicing axis is the grid's z; a column is
// the line of voxels (i, j, 0..nz-1), its centre line (i + 1/2, j + 1/2, z).
//
// Modes (kernels/vox_solid_*.cl, CPU references in reference_inside.h):
//   parity  Exact centre-crossing parity. A triangle crosses column (i, j) when the column centre lies in
//           its xy projection under the centre-mode rule of vox_raster.cl with its top-left tie rule. That
//           rule is the symbolic perturbation of the centre to (x + e, y - e^2): a centre on an edge or
//           vertex shared by a consistently tiled neighbourhood is counted once, on a silhouette twice or
//           never. Each crossing, at its exact depth zc, toggles the first voxel whose centre is at or above
//           it (k = min{k : k + 1/2 >= zc}: a crossing exactly at a centre counts as below it, so a bottom
//           face through centres keeps them inside and a top face leaves them outside, like the surface's
//           half-open slabs). A prefix XOR along z follows: a voxel is inside iff an odd number of crossings
//           lie at or below its centre. On any closed mesh (every edge used an even number of times;
//           orientation does not matter) this equals reference_inside_exact, the +z ray parity, bit for bit.
//   xor     The papers' method (Fang & Chen; TR 1688): the same crossings XOR-blended at the slab granularity
//           of the centre-mode surface voxelization (a crossing in slab [k, k+1) toggles voxel k), then the
//           prefix XOR. That judges each voxel at the top of its slab instead of its centre, moving the
//           boundary down by up to half a voxel: a bottom face crossing in the upper half of voxel k's slab
//           makes k extra, a top face crossing there makes k missing.
//   late    The papers' late filling: each column counts its crossings (all of them, above and below the
//           grid too); an even column is filled by parity (exactly as `parity`), an odd one is
//           "questionable": counted, cleared and repaired from its 4 neighbour columns, voxel by voxel, by
//           the majority of the neighbours already resolved (ties count as inside), in Jacobi rounds until no
//           column changes. Equal to parity on closed meshes (no column is odd).
//   flood   Flood fill of the outside over the conservative surface (SliceVoxelizer, kConservative):
//           outside = the non-surface voxels 6-connected to a non-surface voxel on the grid border, by x, y
//           and z line sweeps repeated until a round changes nothing; inside = the rest (surface voxels
//           included). Closes holes smaller than a voxel and needs no watertight mesh; the interior is up to
//           one voxel layer fatter than the centre rule's (surface voxels whose centre is outside).
// Crossings below the grid toggle voxel 0 and crossings above it toggle nothing, so meshes reaching out of
// the grid's bottom or top still fill; parts outside the grid's x or y range are ignored.
#pragma once

#include <cstdint>
#include <map>
#include <string>

#include "cl/cl_runtime.h"
#include "cl/scratch_buffers.h"
#include "core/grid_spec.h"
#include "core/triangle_soup.h"
#include "voxelize/slice_voxelizer.h"
#include "voxelize/solid_mode.h"
#include "voxelize/voxel_grid.h"

namespace voxr {

struct SolidStats {
  uint64_t inside_voxels = 0;
  uint64_t questionable_columns = 0;  // late: columns with an odd crossing count
  uint64_t repair_iterations = 0;     // late: repair rounds that resolved at least one column
  uint64_t flood_iterations = 0;      // flood: x/y/z sweep rounds, the last one changing nothing
  uint64_t crossing_items = 0;        // work items of vox_solid_cross (triangle, row block)
  double kernels_ms = 0.0;            // profiled kernel time (flood: surface voxelization included)
  std::map<std::string, double> stage_ms;
};

class SolidVoxelizer {
 public:
  explicit SolidVoxelizer(ClRuntime& cl) : cl_(cl), surface_(cl), scratch_(cl) {}

  // Fills grid.inside (and grid.inside_voxels) with the voxels whose CENTRE the mode judges inside;
  // channels = occ + inside. grid.occ holds the conservative surface for kFlood and no voxel for the others
  // (merge with a surface run by taking inside and inside_voxels). Triangles longer than
  // kSplitExtentVoxels are split first (triangle_splitter.h), which can open the mesh where they were.
  VoxelGrid run(const TriangleSoup& soup, const GridSpec& grid, SolidMode mode, SolidStats* stats = nullptr);

 private:
  void run_crossings(const TriangleSoup& soup, const GridSpec& grid, SolidMode mode, cl::Buffer& padded,
                     SolidStats& stats);
  void run_flood(const TriangleSoup& soup, const GridSpec& grid, VoxelGrid& out, cl::Buffer& padded,
                 SolidStats& stats);

  ClRuntime& cl_;
  SliceVoxelizer surface_;  // flood's conservative surface
  ScratchBuffers scratch_;  // device buffers kept between runs
};

}  // namespace voxr
