#include "render/voxel_refraction.h"

#include <cmath>

#include "grid/channel_table.h"
#include "render/visibility_rasterizer.h"
#include "util/error.h"
#include "voxr_layout.h"

namespace voxr {

namespace {

constexpr size_t kGroup = 64;

// Conservative voxelization: a surface leaves no gap a march could slip through (centre mode leaves holes
// where triangles are steep to the slicing axis).
VoxelizeOptions voxelize_options() {
  VoxelizeOptions v;
  v.method = VoxelizeMethod::kHybrid;
  v.mode = RasterMode::kConservative;
  v.channels = ChannelSet::parse("occ,normal,material");
  return v;
}

}  // namespace

VoxelRefraction::VoxelRefraction(ClRuntime& cl, Voxelizer& voxelizer) : cl_(cl), voxelizer_(voxelizer) {}
VoxelRefraction::~VoxelRefraction() = default;

void VoxelRefraction::prepare(const RefractionOptions&) {
  voxelizer_.prepare(voxelize_options());
  cl_.build_programs({{"refract_voxel.cl", channel_defines()}});
}

void VoxelRefraction::set_scene(const TriangleSoup& soup, const DeviceMesh& scene_mesh) {
  soup_ = &soup;
  scene_mesh_ = &scene_mesh;
  bounds_ = scene_mesh.bounds();
  mesh_.reset();
  voxelized_ = nullptr;
}

void VoxelRefraction::build(const RefractionOptions& options) {
  if (soup_ == nullptr) fail("voxel refraction: no scene was set");
  if (options.resolution < 2 || options.resolution > kMaxGridDim)
    fail("--res: the refraction grid needs 2..{} voxels along its longest side (got {})", kMaxGridDim,
         options.resolution);
  GridRequest request;
  request.resolution = options.resolution;
  const GridSpec spec = fit_grid(bounds_, request, soup_->anchor);
  // The split mesh depends on the grid only: reuse it while the scene and the grid stay.
  if (!voxelized_ || mesh_grid_.dims != spec.dims || mesh_grid_.voxel_size != spec.voxel_size ||
      mesh_grid_.origin != spec.origin) {
    mesh_ = upload_split_mesh(cl_, *soup_, spec, SplitCull::kGrid);
    voxelized_ = mesh_ ? mesh_.get() : scene_mesh_;
    mesh_grid_ = spec;
  }
  voxelizer_.run(*voxelized_, spec, voxelize_options(), grid_);
  if (!grid_.has_rank_index) build_rank_index(cl_, grid_);

  for (int a = 0; a < 3; ++a) brick_dims_[a] = (spec.dims[a] + VOXR_BRICK - 1) / VOXR_BRICK;
  const uint64_t brick_words = (uint64_t(brick_dims_.x) * brick_dims_.y * brick_dims_.z + 31) / 32;
  cl::Buffer& bricks = bricks_.ensure(cl_, brick_words * 4, "refraction bricks");
  cl_.queue().enqueueFillBuffer(bricks, cl_uint(0), 0, brick_words * 4);
  cl::Kernel kernel = cl_.kernel("refract_voxel.cl", "brick_occupancy", channel_defines());
  cl_.launch("refraction_bricks", kernel, grid_.words(), kGroup, grid_.view_args(cl_), params(options),
             cl_ulong(grid_.words()), bricks);
}

VoxelRefractParams VoxelRefraction::params(const RefractionOptions& options) const {
  const GridSpec& spec = grid_.spec;
  VoxelRefractParams p{};
  for (int a = 0; a < 3; ++a) {
    p.origin[a] = spec.origin[a];
    p.brick_dims[a] = brick_dims_[a];
  }
  p.voxel_size = spec.voxel_size;
  p.two_surface = options.method == RefractionMethod::kVoxelTwo ? 1u : 0u;
  p.step_dda = options.step == StepRule::kDda ? 1u : 0u;
  p.smooth_normals = options.normals == NormalKind::kSmooth ? 1u : 0u;
  p.cos_threshold = std::cos(options.angle_threshold_deg * float(M_PI) / 180.0f);
  p.max_steps = 4 * (spec.dims.x + spec.dims.y + spec.dims.z);
  return p;
}

void VoxelRefraction::trace(const CameraFrame& camera, const cl::Buffer& primary_samples,
                            const DielectricPixels& dielectric, const cl::Buffer& materials,
                            uint32_t material_count, const RefractionOptions& options,
                            cl::Buffer& end_samples, cl::Buffer& paths) {
  VOXR_CHECK(material_count > 0);
  cl::Kernel kernel = cl_.kernel("refract_voxel.cl", "refract_voxel", channel_defines());
  VOXR_CHECK_EQ(uint64_t(dielectric.pixel_count()), uint64_t(camera.width) * camera.height);
  cl_.launch("refraction", kernel, dielectric.pixel_count(), kGroup, grid_.view_args(cl_),
             make_render_camera(camera), primary_samples, dielectric, materials, cl_uint(material_count),
             params(options), bricks_.buffer, end_samples, paths);
}

}  // namespace voxr
