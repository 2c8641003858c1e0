// NumPy .npz output: the set voxels as a sparse list, for Python (`np.load("out.npz")`). A .npz is a zip of
// .npy arrays; voxr writes it through zlib's minizip (stored, not deflated: the arrays are written at disk
// speed; ZIP64 entries and directory when the archive may pass 4 GiB).
//
// Arrays (little endian, C order):
//   ijk        int32   N x 3   voxel indices (i, j, k) of the N set voxels, in brick order: 8^3 bricks in
//                              increasing linear brick index (z slowest), within a brick z, then y, then x
//                              slowest to fastest (SparseVoxelGrid's order; np.lexsort(ijk.T) gives linear
//                              order, k slowest)
//   count      uint32  N       per channel present, row r belongs to ijk[r]
//   normal     float32 N x 3   unit normal in the grid's frame
//   material   uint32  N
//   dims       uint32  3       grid dimensions
//   voxel_size float64 ()      voxel edge length
//   origin     float64 3       world centre of voxel (0, 0, 0)
//   axes       float64 3 x 3   row a = the grid's axis a in world coordinates, so the world centre of voxel
//                              ijk is origin + voxel_size * ijk @ axes
// The interior (--solid's inside channel) is not written: the list holds the surface voxels.
#pragma once

#include <filesystem>

#include "grid/sparse_voxel_grid.h"
#include "grid/voxel_grid.h"

namespace voxr {

// Writes `grid` to `out` and returns `out`. Throws voxr::Error naming `out` on failure; nothing is left.
std::filesystem::path write_npz(const SparseVoxelGrid& grid, const std::filesystem::path& out);
// The dense grid through to_sparse (memory of its set voxels, not of the volume): the same bytes.
std::filesystem::path write_npz(const VoxelGrid& grid, const std::filesystem::path& out);

}  // namespace voxr
