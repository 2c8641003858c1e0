// Solid fill: which voxel centres lie inside the mesh (the inside channel of a DeviceVoxelGrid). The slicing
// axis is the grid's z; a column is the line of voxels (i, j, 0..nz-1), its centre line (i + 1/2, j + 1/2,
// z).
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
//   flood   Flood fill of the outside over the conservative surface (the run's own surface when it is
//           conservative and of the slice family, else a hybrid conservative surface of its own):
//           outside = the non-surface voxels 6-connected to a non-surface voxel on the grid border, by x, y
//           and z line sweeps repeated until a round changes nothing; inside = the rest (surface voxels
//           included). Closes holes smaller than a voxel and needs no watertight mesh; the interior is up to
//           one voxel layer fatter than the centre rule's (surface voxels whose centre is outside).
// Crossings below the grid toggle voxel 0 and crossings above it toggle nothing, so meshes reaching out of
// the grid's bottom or top still fill; parts outside the grid's x or y range are ignored.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "cl/scratch_buffers.h"
#include "voxelize/voxelizer.h"

namespace voxr {

class SliceVoxelizer;

class SolidFill {
 public:
  explicit SolidFill(ClRuntime& cl);
  ~SolidFill();

  // The programs a fill in `mode` builds (flood includes its conservative surface's).
  std::vector<ProgramSpec> programs(SolidMode mode) const;

  // Fills out.inside (dense bits) and out.inside_voxels with the voxels whose CENTRE `mode` judges inside.
  // `surface_is_conservative`: out.occ already holds the conservative surface (flood uses it). The mesh
  // should be uploaded with SplitCull::kColumns (crossings below and above the grid count). stats receive
  // the solid counters.
  void run(const DeviceMesh& mesh, const GridSpec& grid, SolidMode mode, bool surface_is_conservative,
           DeviceVoxelGrid& out, VoxelizeStats& stats);

 private:
  void run_crossings(const DeviceMesh& mesh, const GridSpec& grid, SolidMode mode, cl::Buffer& padded,
                     VoxelizeStats& stats);
  void run_flood(const DeviceMesh& mesh, const GridSpec& grid, const cl::Buffer& surface, cl::Buffer& padded,
                 VoxelizeStats& stats);

  ClRuntime& cl_;
  std::unique_ptr<SliceVoxelizer> surface_;  // flood's own conservative surface, when the run has none
  DeviceVoxelGrid surface_grid_;
  ScratchBuffers scratch_;  // device buffers kept between runs
};

}  // namespace voxr
