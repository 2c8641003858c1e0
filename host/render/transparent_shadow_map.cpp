#include "render/transparent_shadow_map.h"

#include <cmath>

#include "grid/channel_table.h"
#include "util/error.h"

namespace voxr {

namespace {

constexpr size_t kGroup = 64;
// shadow_transmittance.cl SHADOW_*
constexpr uint32_t kShadowVoxel = 0, kShadowUniform = 1, kShadowUniformOpaque = 2;

VoxelizeOptions voxelize_options(const ShadowMapOptions& options) {
  VoxelizeOptions v;
  if (options.method == ShadowMethod::kUniform) {
    v.method = VoxelizeMethod::kSlicemap;
  } else {
    VOXR_CHECK(options.method == ShadowMethod::kVoxel);
    v.method = VoxelizeMethod::kHybrid;
    v.mode = options.mode;
    v.channels = ChannelSet::parse("occ,count,material");
  }
  return v;
}

}  // namespace

TransparentShadowMap::TransparentShadowMap(ClRuntime& cl, Voxelizer& voxelizer)
    : cl_(cl), voxelizer_(voxelizer) {}

void TransparentShadowMap::prepare(const ShadowMapOptions& options) {
  voxelizer_.prepare(voxelize_options(options));
  cl_.build_programs({{"shadow_transmittance.cl", channel_defines()}, {"shadow_lookup.cl", {}}});
}

void TransparentShadowMap::build(const DeviceMesh& light_mesh, const LightFrame& frame,
                                 const cl::Buffer& materials, uint32_t material_count,
                                 const glm::vec3& uniform_tau, bool uniform_blocks,
                                 const ShadowMapOptions& options, VoxelizeStats* stats) {
  VOXR_CHECK(material_count > 0);
  frame_ = frame;
  const glm::uvec3 d = frame.grid.dims;
  const uint64_t volume_bytes = uint64_t(d.x) * d.y * d.z * 4;
  if (volume_bytes > cl_.device().max_allocation)
    fail(
        "--shadow-res: the transmittance volume of the light grid {} x {} x {} needs {:.0f} MiB, more than "
        "the "
        "largest buffer {} allows ({:.0f} MiB); use a smaller --shadow-res",
        d.x, d.y, d.z, double(volume_bytes) / (1 << 20), cl_.device().name,
        double(cl_.device().max_allocation) / (1 << 20));
  const VoxelizeOptions vopt = voxelize_options(options);
  voxelizer_.run(light_mesh, frame.grid, vopt, grid_, stats);
  if (!grid_.has_rank_index && options.method == ShadowMethod::kVoxel) build_rank_index(cl_, grid_);
  const uint64_t columns = uint64_t(frame.grid.dims.x) * frame.grid.dims.y;
  cl::Buffer& volume = volume_.ensure(cl_, columns * frame.grid.dims.z * 4, "transmittance volume");
  cl::Kernel kernel = cl_.kernel("shadow_transmittance.cl", "shadow_transmittance", channel_defines());
  const uint32_t method = options.method != ShadowMethod::kUniform ? kShadowVoxel
                          : uniform_blocks                         ? kShadowUniformOpaque
                                                                   : kShadowUniform;
  cl::Buffer& tails = tails_.ensure(cl_, columns * 8, "transmittance volume tails");
  cl_.launch("shadow_transmittance", kernel, columns, kGroup, grid_.view_args(cl_), frame.params, materials,
             cl_uint(material_count), cl_uint(method),
             cl_uint(options.mode == RasterMode::kConservative ? 1 : 0), uniform_tau.x, uniform_tau.y,
             uniform_tau.z, volume, tails);
}

void TransparentShadowMap::lookup(const cl::Buffer& samples, uint32_t count, const cl::Buffer& materials,
                                  uint32_t material_count, const RenderLight& light,
                                  const ShadowMapOptions& options, cl::Buffer& transmittance,
                                  const cl::Buffer* opaque_depth) {
  cl::Kernel kernel = cl_.kernel("shadow_lookup.cl", "shadow_lookup");
  // Conservative grids mark every voxel a receiver's own surface touches in a column: half the plane's
  // depth span over a column before its crossing (shadow_frame.h sf_column_depth).
  const float slope_bias =
      options.method == ShadowMethod::kVoxel && options.mode == RasterMode::kConservative ? 0.5f : 0.0f;
  cl_.launch("shadow_lookup", kernel, count, kGroup, samples, cl_uint(count), materials,
             cl_uint(material_count), light, frame_.params, volume_.buffer, tails_.buffer,
             opaque_depth ? *opaque_depth : tails_.buffer, cl_uint(opaque_depth ? 1 : 0), options.bias,
             slope_bias, options.normal_offset, transmittance);
}

uint64_t TransparentShadowMap::device_bytes() const {
  return grid_.device_bytes() + volume_.bytes + tails_.bytes;
}

UniformAbsorption uniform_absorption(const TriangleSoup& soup, const std::vector<Material>& materials) {
  UniformAbsorption u;
  for (const glm::uvec4& t : soup.triangles) {
    if (t.w >= materials.size()) continue;
    const Material& m = materials[t.w];
    if (m.kind == MaterialKind::kSheet) {
      u.sheet_depth += -glm::log(glm::max(glm::dvec3(m.transmittance), glm::dvec3(1e-30)));
      ++u.triangles;
    } else if (m.kind == MaterialKind::kDielectric) {
      u.absorption += glm::dvec3(m.absorption);
      ++u.triangles;
    } else {
      ++u.opaque;
    }
  }
  return u;
}

glm::vec3 UniformAbsorption::at(float voxel_length) const {
  if (triangles == 0) return glm::vec3(0.0f);
  return glm::vec3((sheet_depth + absorption * double(voxel_length)) / double(triangles));
}

}  // namespace voxr
