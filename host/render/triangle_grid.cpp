#include "render/triangle_grid.h"

#include "core/grid_spec.h"
#include "util/error.h"
#include "voxelize/triangle_splitter.h"

namespace voxr {

void TriangleGridArgs::set_kernel_args(cl::Kernel& kernel, cl_uint& index) const {
  grid.set_kernel_args(kernel, index);
  kernel.setArg(index++, *offsets);
  kernel.setArg(index++, *ids);
  kernel.setArg(index++, capacity);
  kernel.setArg(index++, *positions);
  kernel.setArg(index++, *triangles);
}

TriangleGrid::TriangleGrid(ClRuntime& cl, Voxelizer& voxelizer) : cl_(cl), voxelizer_(voxelizer) {}

VoxelizeOptions TriangleGrid::voxelize_options() {
  VoxelizeOptions v;
  v.method = VoxelizeMethod::kHybrid;
  v.mode = RasterMode::kConservative;
  v.channels = ChannelSet::parse("occ,count");
  v.triangle_lists = true;
  return v;
}

void TriangleGrid::build(const DeviceMesh& mesh, uint32_t resolution) {
  if (resolution < 2 || float(resolution) > kSplitExtentVoxels)
    fail(
        "the triangle lists need 2..{:.0f} voxels along the grid's longest side (got {}): beyond that "
        "triangles would have to be split, and the lists hold the mesh's own triangles",
        kSplitExtentVoxels, resolution);
  if (mesh.triangle_count() == 0) fail("the triangle lists need a mesh with triangles");
  GridRequest request;
  request.resolution = resolution;
  const GridSpec spec = fit_grid(mesh.bounds(), request, mesh.anchor());
  mesh_ = &mesh;
  voxelizer_.run(mesh, spec, voxelize_options(), grid_);
}

const DeviceMesh& TriangleGrid::mesh() const {
  if (mesh_ == nullptr) throw InternalError("TriangleGrid::mesh before build");
  return *mesh_;
}

TriangleGridArgs TriangleGrid::view_args() {
  if (!grid_.has_triangle_lists) throw InternalError("TriangleGrid::view_args before build");
  TriangleGridArgs a;
  a.grid = grid_.view_args(cl_);
  a.offsets = &grid_.list_offsets.buffer;
  a.ids = &grid_.list_ids.buffer;
  a.capacity = grid_.list_capacity;
  a.positions = &mesh_->positions();
  a.triangles = &mesh_->triangles();
  return a;
}

TriangleGrids::TriangleGrids(ClRuntime& cl, Voxelizer& voxelizer) : cl_(cl), voxelizer_(voxelizer) {}
TriangleGrids::~TriangleGrids() = default;

void TriangleGrids::begin_frame() {
  for (auto& [resolution, entry] : grids_) entry.fresh = false;
}

TriangleGrid& TriangleGrids::get(const DeviceMesh& mesh, uint32_t resolution) {
  Entry& e = grids_[resolution];
  if (!e.grid) e.grid = std::make_unique<TriangleGrid>(cl_, voxelizer_);
  if (!e.fresh || &e.grid->mesh() != &mesh) {
    e.grid->build(mesh, resolution);
    e.fresh = true;
  }
  return *e.grid;
}

uint64_t TriangleGrids::device_bytes() const {
  uint64_t bytes = 0;
  for (const auto& [resolution, entry] : grids_) bytes += entry.grid ? entry.grid->device_bytes() : 0;
  return bytes;
}

}  // namespace voxr
