// The C interface between voxr's .vdb writer (io/vdb_writer.cpp) and the OpenVDB plugin that writes the file
// (peers/openvdb_writer.cpp, in libvoxr_openvdb_peer.so, loaded by dlopen only when a .vdb is written).
// Plain pointers and sizes of a SparseVoxelGrid's arrays: nothing of voxr's C++ types crosses the boundary,
// and a new channel (e.g. colour) is one more VoxrVdbChannel, not a new entry point.
#pragma once

#include <stddef.h>
#include <stdint.h>

extern "C" {

// Bumped when the structs below change; the plugin refuses another version.
#define VOXR_VDB_ABI_VERSION 1

enum VoxrVdbValueType : uint32_t {
  kVoxrVdbInt32 = 0,    // int32 (voxr's uint32 channels, bit for bit) -> openvdb::Int32Grid
  kVoxrVdbFloat32 = 1,  // float, 1 component -> FloatGrid; 3 components -> Vec3SGrid
};

enum VoxrVdbCompression : uint32_t {
  kVoxrVdbNone = 0,     // raw leaf buffers (active-mask compression only)
  kVoxrVdbZip = 1,      // zlib
  kVoxrVdbBlosc = 2,    // Blosc (LZ4), when the OpenVDB build has it (else the plugin reports an error)
  kVoxrVdbDefault = 3,  // Blosc when the OpenVDB build has it, else zip
};

// One attribute grid: voxels_set entries of `components` values in the bricks' order (brick order).
struct VoxrVdbChannel {
  const char* name;  // the grid's name ("count", "normal", "material", ...)
  uint32_t type;     // VoxrVdbValueType
  uint32_t components;
  const void* values;
  uint32_t vector_normal;  // 1: a unit normal in index space (VEC_COVARIANT_NORMALIZE, not in world space)
};

struct VoxrVdbWrite {
  uint32_t abi_version;         // VOXR_VDB_ABI_VERSION
  const char* path;             // the file to create (the AtomicFile's temporary)
  uint32_t dims[3];             // grid dimensions (stored as the grids' "voxr_dims" metadata)
  uint32_t brick_dims[3];       // bricks along each axis
  uint64_t bricks;              // stored bricks
  const uint64_t* brick_index;  // linear brick index of each brick, increasing
  const uint32_t* brick_bits;   // 16 words per brick, bit x + 8 * (y + 8 * z)
  const uint64_t* brick_rank;   // set voxels before each brick (bricks + 1)
  double index_to_world[16];    // row-vector 4x4 (OpenVDB's convention): rows 0-2 the index axes, row 3 the
                                // world position of index (0, 0, 0)
  uint32_t axis_aligned;        // 1: rows 0-2 are voxel_size times the unit axes (a scale-translate map)
  double voxel_size;
  uint32_t compression;  // VoxrVdbCompression
  uint32_t channel_count;
  const VoxrVdbChannel* channels;
  const char* creator;  // file and grid metadata "creator"
};

// Writes `occupancy` (BoolGrid) and one grid per channel to write->path, all with the same transform, leaf
// nodes built from the bricks. Returns false with a one-line message in `error` on failure.
bool voxr_openvdb_write(const VoxrVdbWrite* write, char* error, size_t error_size);
}
