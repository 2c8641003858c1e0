#include "render/voxel_refraction.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "grid/channel_table.h"
#include "render/triangle_grid.h"
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

// The kernel's view of one built level.
VoxelLevelParams level_params(const DeviceVoxelGrid& grid, const glm::uvec3& brick_dims) {
  VoxelLevelParams p{};
  for (int a = 0; a < 3; ++a) {
    p.origin[a] = grid.spec.origin[a];
    p.brick_dims[a] = brick_dims[a];
  }
  p.voxel_size = grid.spec.voxel_size;
  p.present = 1u;
  return p;
}

}  // namespace

VoxelRefraction::VoxelRefraction(ClRuntime& cl, Voxelizer& voxelizer) : cl_(cl), voxelizer_(voxelizer) {}
VoxelRefraction::~VoxelRefraction() = default;

void VoxelRefraction::prepare(const RefractionOptions&) {
  voxelizer_.prepare(voxelize_options());
  std::vector<ProgramSpec> programs = TriangleGrid::programs();  // the empty-space bits, one kernel for both
  programs.push_back({"refract_voxel.cl", channel_defines()});
  cl_.build_programs(programs);
}

void VoxelRefraction::set_scene(const TriangleSoup& soup, const DeviceMesh& scene_mesh,
                                const std::vector<Material>& materials) {
  for (Level* level : {&fine_, &coarse_}) {
    level->mesh.reset();
    level->voxelized = nullptr;
  }
  // Material ranks by kind: the voxelizer's atomic max then keeps opaque over sheet over dielectric.
  const auto priority = [](MaterialKind k) {
    return k == MaterialKind::kDielectric ? 0 : k == MaterialKind::kSheet ? 1 : 2;
  };
  std::vector<uint32_t> material_of(std::max<size_t>(1, materials.size()));
  std::iota(material_of.begin(), material_of.end(), 0u);
  std::stable_sort(material_of.begin(), material_of.begin() + materials.size(), [&](uint32_t a, uint32_t b) {
    return priority(materials[a].kind) < priority(materials[b].kind);
  });
  std::vector<uint32_t> rank(material_of.size());
  for (uint32_t r = 0; r < material_of.size(); ++r) rank[material_of[r]] = r;
  const bool identity = std::is_sorted(material_of.begin(), material_of.end());
  ranked_mesh_.reset();
  ranked_soup_ = TriangleSoup{};
  if (identity) {
    soup_ = &soup;
    scene_mesh_ = &scene_mesh;
  } else {
    ranked_soup_ = soup;
    for (glm::uvec4& t : ranked_soup_.triangles)
      if (t.w < rank.size()) t.w = rank[t.w];
    const Bounds bounds = scene_mesh.bounds();
    ranked_mesh_ = std::make_unique<DeviceMesh>(cl_, ranked_soup_, &bounds);
    soup_ = &ranked_soup_;
    scene_mesh_ = ranked_mesh_.get();
  }
  cl::Buffer& order = material_of_.ensure(cl_, material_of.size() * 4, "refraction material order");
  cl_.upload(order, material_of.data(), material_of.size() * 4, "refraction material order");
  bounds_ = scene_mesh.bounds();
  dielectric_bounds_ = Bounds{};
  for (const glm::uvec4& t : soup.triangles)
    if (t.w < materials.size() && materials[t.w].kind == MaterialKind::kDielectric)
      for (int c = 0; c < 3; ++c) dielectric_bounds_.extend(glm::vec3(soup.positions[t[c]]));
}

VoxelRefraction::Levels VoxelRefraction::grids(const RefractionOptions& options) const {
  if (soup_ == nullptr) fail("voxel refraction: no scene was set");
  if (options.resolution < 2 || options.resolution > kMaxGridDim)
    fail("--res: the refraction grid needs 2..{} voxels along its longest side (got {})", kMaxGridDim,
         options.resolution);
  Levels out;
  GridRequest request;
  request.resolution = options.resolution;
  if (options.grid == RefractionGrid::kScene || dielectric_bounds_.empty()) {
    out.fine = fit_grid(bounds_, request, soup_->anchor);
    return out;
  }
  request.margin_voxels = kFineMarginVoxels;
  out.fine = fit_grid(dielectric_bounds_, request, soup_->anchor);
  Bounds all = bounds_;
  all.extend(out.fine.origin);
  all.extend(out.fine.origin + glm::vec3(out.fine.dims) * out.fine.voxel_size);
  GridRequest coarse;
  coarse.resolution = options.coarse_resolution != 0 ? options.coarse_resolution
                                                     : std::max(2u, options.resolution / kCoarseDivisor);
  out.coarse = fit_grid(all, coarse, soup_->anchor);
  return out;
}

void VoxelRefraction::build_level(Level& level, const GridSpec& spec) {
  // The split mesh depends on the grid only: reuse it while the scene and the grid stay.
  if (!level.voxelized || level.mesh_grid.dims != spec.dims ||
      level.mesh_grid.voxel_size != spec.voxel_size || level.mesh_grid.origin != spec.origin) {
    level.mesh = upload_split_mesh(cl_, *soup_, spec, SplitCull::kGrid);
    level.voxelized = level.mesh ? level.mesh.get() : scene_mesh_;
    level.mesh_grid = spec;
  }
  voxelizer_.run(*level.voxelized, spec, voxelize_options(), level.grid);
  if (!level.grid.has_rank_index) build_rank_index(cl_, level.grid);

  for (int a = 0; a < 3; ++a) level.brick_dims[a] = (spec.dims[a] + VOXR_BRICK - 1) / VOXR_BRICK;
  const uint64_t brick_words =
      (uint64_t(level.brick_dims.x) * level.brick_dims.y * level.brick_dims.z + 31) / 32;
  cl::Buffer& bricks = level.bricks.ensure(cl_, brick_words * 4, "refraction bricks");
  cl_.queue().enqueueFillBuffer(bricks, cl_uint(0), 0, brick_words * 4);
  const ProgramSpec brick_program = TriangleGrid::programs().front();
  cl::Kernel kernel = cl_.kernel(brick_program.file, "triangle_bricks", brick_program.defines);
  const cl_uint4 dims = {{spec.dims.x, spec.dims.y, spec.dims.z, 0}};
  const cl_uint4 bdims = {{level.brick_dims.x, level.brick_dims.y, level.brick_dims.z, 0}};
  cl_.launch("refraction_bricks", kernel, level.grid.words(), kGroup, level.grid.occ.buffer,
             cl_ulong(level.grid.words()), dims, bdims, bricks);
}

void VoxelRefraction::build(const RefractionOptions& options) {
  const Levels levels = grids(options);
  build_level(fine_, levels.fine);
  coarse_present_ = levels.coarse.has_value();
  if (coarse_present_) build_level(coarse_, *levels.coarse);
}

uint64_t VoxelRefraction::device_bytes() const {
  return fine_.grid.device_bytes() + (coarse_present_ ? coarse_.grid.device_bytes() : 0);
}

VoxelRefractParams VoxelRefraction::params(const RefractionOptions& options) const {
  VoxelRefractParams p{};
  p.fine = level_params(fine_.grid, fine_.brick_dims);
  if (coarse_present_) p.coarse = level_params(coarse_.grid, coarse_.brick_dims);
  p.two_surface = options.method == RefractionMethod::kVoxelTwo ? 1u : 0u;
  p.step_dda = options.step == StepRule::kDda ? 1u : 0u;
  p.smooth_normals = options.normals == NormalKind::kSmooth ? 1u : 0u;
  p.cos_threshold = std::cos(options.angle_threshold_deg * float(M_PI) / 180.0f);
  const glm::uvec3 d = fine_.grid.spec.dims;
  p.max_steps = 4 * (d.x + d.y + d.z);
  if (coarse_present_) {
    const glm::uvec3 c = coarse_.grid.spec.dims;
    p.max_steps += 4 * (c.x + c.y + c.z);
  }
  return p;
}

void VoxelRefraction::trace(const CameraFrame& camera, const cl::Buffer& primary_samples,
                            const DielectricPixels& dielectric, const cl::Buffer& materials,
                            uint32_t material_count, const RefractionOptions& options,
                            cl::Buffer& end_samples, cl::Buffer& paths) {
  VOXR_CHECK(material_count > 0);
  cl::Kernel kernel = cl_.kernel("refract_voxel.cl", "refract_voxel", channel_defines());
  VOXR_CHECK_EQ(uint64_t(dielectric.pixel_count()), uint64_t(camera.width) * camera.height);
  // Without a coarse level the fine one stands in for it, unread (params: coarse.present 0).
  Level& coarse = coarse_present_ ? coarse_ : fine_;
  cl_.launch("refraction", kernel, dielectric.pixel_count(), kGroup, fine_.grid.view_args(cl_),
             coarse.grid.view_args(cl_), make_render_camera(camera), primary_samples, dielectric, materials,
             cl_uint(material_count), params(options), fine_.bricks.buffer, coarse.bricks.buffer,
             material_of_.buffer, end_samples, paths);
}

}  // namespace voxr
