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
  kernel.setArg(index++, *bricks);
  kernel.setArg(index++, brick_dims);
}

TriangleGrid::TriangleGrid(ClRuntime& cl, Voxelizer& voxelizer) : cl_(cl), voxelizer_(voxelizer) {}

namespace {

constexpr size_t kGroup = 64;

Defines brick_defines() {
  return {{"WG_SIZE", std::to_string(kGroup)}};
}

}  // namespace

std::vector<ProgramSpec> TriangleGrid::programs() {
  return {{"triangle_bricks.cl", brick_defines()}};
}

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

  for (int a = 0; a < 3; ++a) brick_dims_[a] = (spec.dims[a] + VOXR_BRICK - 1) / VOXR_BRICK;
  brick_words_ = (uint64_t(brick_dims_.x) * brick_dims_.y * brick_dims_.z + 31) / 32;
  cl::Buffer& bricks = bricks_.ensure(cl_, brick_words_ * 4, "triangle list bricks");
  cl_.fill_zero(bricks, brick_words_ * 4, "clear");
  cl::Kernel kernel = cl_.kernel("triangle_bricks.cl", "triangle_bricks", brick_defines());
  const cl_uint4 dims = {{spec.dims.x, spec.dims.y, spec.dims.z, 0}};
  const cl_uint4 bdims = {{brick_dims_.x, brick_dims_.y, brick_dims_.z, 0}};
  cl_.launch("lists", kernel, grid_.words(), kGroup, grid_.occ.buffer, cl_ulong(grid_.words()), dims, bdims,
             bricks);
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
  a.bricks = &bricks_.buffer;
  a.brick_dims = {{brick_dims_.x, brick_dims_.y, brick_dims_.z, 0}};
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
