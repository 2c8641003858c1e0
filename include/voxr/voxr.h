// voxr's public C++ API: voxelize triangle meshes on an OpenCL device (PoCL on a CPU, a GPU driver) into
// grids with per-voxel attributes, and write them by file extension. This header is all a program that
// links voxr::voxr sees (find_package(voxr), docs/library.md); the Python package binds the same functions.
//
// Frames and units: positions are in the caller's world units (double); voxel (i, j, k) is the box
// [i, i+1] x [j, j+1] x [k, k+1] in grid units, mapped to the world by VoxelVolume::index_to_world; linear
// index = (k * ny + j) * nx + i (x fastest). The methods are those of `voxr voxelize` (docs/methods.md:
// Chang & Lai's slice voxelization and its hybrid, Llamas' Grid, Eisemann & Decoret's slicemaps); the same
// mesh and settings give the same voxels as the CLI, bit for bit.
//
// Errors: every function throws voxr::Error (a std::runtime_error) with voxr's one-line message for bad
// input (a file that cannot be read, an unknown method, an index out of range, a grid the device cannot
// hold); nothing calls exit() or aborts on bad input.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "voxr/error.h"

namespace voxr {

// One OpenCL device as `voxr devices` lists it.
struct DeviceDescription {
  std::string id;        // "P:D", what VoxelizeSettings::device and --device take
  std::string name;      // the device's name
  std::string platform;  // the platform's name
  std::string type;      // "GPU", "CPU", "accelerator" or "other"
  std::string driver_version;
  uint32_t compute_units = 0;
  uint64_t global_memory = 0;   // bytes
  uint64_t max_allocation = 0;  // bytes, the largest single buffer
};

// Every OpenCL device of every platform. Throws voxr::Error when there is no OpenCL platform.
VOXR_API std::vector<DeviceDescription> devices();

// A triangle mesh the caller owns, read in place (no copy is kept after voxelize returns).
// positions: vertex_count x 3 doubles (x, y, z, row-major); triangles: triangle_count x 3 vertex indices;
// materials: empty or triangle_count material ids (the material channel keeps the largest per voxel).
struct MeshView {
  std::span<const double> positions;
  std::span<const uint32_t> triangles;
  std::span<const uint32_t> materials;
  std::string name = "mesh";  // names the mesh in error messages
};

// What `voxr voxelize` takes as flags, with the same defaults and names (docs/cli.md).
struct VoxelizeSettings {
  uint32_t resolution = 0;  // --res: voxels along the bounds' longest side; 0: the scene's grid (default 256)
  std::optional<std::array<uint32_t, 3>> dims;  // --dims: exact dimensions instead of resolution
  std::optional<std::array<double, 6>> bounds;  // --bounds x0,y0,z0,x1,y1,z1 (world), used exactly
  std::string method = "hybrid";                // hybrid, slice, grid, slicemap
  std::string mode;                             // conservative (empty: the default) or center
  std::string slicing;                          // slicemap only: uniform (empty: the default) or local
  std::string channels = "occ";                 // comma list of occ,count,normal,material,color
  std::string solid;                            // empty, xor, late, parity or flood (adds `inside`)
  std::string layout = "auto";                  // auto, dense or sparse
  std::string memory_budget;                    // a sparse run's device memory, "512M", "4G"; empty: default
  std::string device;  // "P:D", "P", a name substring; empty: $VOXR_DEVICE or default
};

// Timings and counts of one voxelization (the `ms` and count fields of the CLI's --report).
struct VoxelizeReport {
  uint64_t triangles = 0;
  uint64_t voxels_set = 0;
  uint64_t inside_voxels = 0;
  uint64_t device_bytes = 0;  // peak device memory of the run
  double upload_ms = 0, kernels_ms = 0, readback_ms = 0, wall_ms = 0;
  std::string layout;                 // "dense" or "sparse"
  std::vector<std::string> warnings;  // what the CLI prints as "voxr: warning: ..."
  std::string json;  // the same object as `voxr voxelize --report`, for the fields above and more
};

// A voxelization result. Occupancy covers the grid; the attribute channels hold one entry per set voxel, in
// the order occupied_indices() lists the voxels (increasing linear index for the dense layout, brick by
// brick for the sparse one).
class VOXR_API VoxelVolume {
 public:
  struct Impl;
  explicit VoxelVolume(std::shared_ptr<const Impl> impl);

  std::array<uint32_t, 3> dims() const;
  double voxel_size() const;                      // world units
  std::array<double, 16> index_to_world() const;  // column-major 4x4: grid units (i, j, k, 1) -> world
  std::string channels() const;                   // e.g. "occ,count,normal" (+ "inside" with a solid)
  bool sparse() const;  // built in 8^3 bricks (layout sparse or auto on a large grid)
  uint64_t voxels_set() const;
  uint64_t inside_voxels() const;
  const VoxelizeReport& report() const;

  // Dense 0/1 bytes, dims[0] * dims[1] * dims[2] of them in linear order (x fastest), into `out`.
  // Throws voxr::Error if out.size() is not the voxel count. inside: the solid's interior bits (empty grid
  // if the run had no solid).
  void occupancy(std::span<uint8_t> out) const;
  void inside(std::span<uint8_t> out) const;
  // The set voxels' (i, j, k), voxels_set() x 3, into `out` (size checked as above).
  void occupied_indices(std::span<uint32_t> out) const;

  // Views of the attribute channels (empty when not requested): voxels_set() entries each.
  std::span<const uint32_t> count() const;     // triangles that wrote the voxel
  std::span<const float> normal() const;       // 3 floats per voxel: mean unit normal (0 where they cancel)
  std::span<const uint32_t> material() const;  // largest material id
  std::span<const uint8_t> color() const;      // 4 bytes per voxel: mean base colour RGBA8

  // Writes the volume by extension (.vdb, .npz, .nrrd, .vti, .binvox, .vox) atomically; returns the files
  // written (.nrrd writes one per channel). Throws voxr::Error naming `path` on a bad extension or folder.
  std::vector<std::string> save(const std::string& path) const;

 private:
  std::shared_ptr<const Impl> impl_;
};

// An OpenCL device opened with its programs built (or loaded from the program cache), kept for many runs:
// a Context per device per process (or per Dask worker) pays the driver's start once.
// Thread-compatible: one run at a time per Context.
class VOXR_API Context {
 public:
  // Throws voxr::Error when `device` selects nothing.
  explicit Context(const std::string& device = "");
  ~Context();
  Context(Context&&) noexcept;
  Context& operator=(Context&&) noexcept;

  DeviceDescription device() const;
  // Voxelizes `mesh` as `settings` say (settings.device is ignored: the Context's device runs).
  VoxelVolume voxelize(const MeshView& mesh, const VoxelizeSettings& settings);
  // Reads a mesh or scene file (docs/mesh-files.md, docs/scene-format.md) and voxelizes it as
  // `voxr voxelize FILE` does.
  VoxelVolume voxelize_file(const std::string& path, const VoxelizeSettings& settings);

 private:
  struct State;
  std::unique_ptr<State> state_;
};

// One-shot forms on a Context kept per device for the process (thread-safe).
VOXR_API VoxelVolume voxelize(const MeshView& mesh, const VoxelizeSettings& settings = {});
VOXR_API VoxelVolume voxelize_file(const std::string& path, const VoxelizeSettings& settings = {});

// The library's version, "major.minor.patch".
VOXR_API std::string version();

}  // namespace voxr
