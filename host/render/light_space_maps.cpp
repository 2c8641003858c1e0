#include "render/light_space_maps.h"

#include "util/error.h"

namespace voxr {

namespace {

constexpr size_t kGroup = 64;
constexpr uint32_t kOpaqueKinds = 1u << VOXR_MATERIAL_OPAQUE;
constexpr uint32_t kTransparentKinds = (1u << VOXR_MATERIAL_SHEET) | (1u << VOXR_MATERIAL_DIELECTRIC);
constexpr uint32_t kAllKinds = kOpaqueKinds | kTransparentKinds;

// The light's view of `frame` for the rasterizer, one texel per column, drawing the material kinds of
// `kind_mask`.
RasterTarget light_target(const LightFrame& frame, uint32_t kind_mask) {
  RasterTarget target;
  target.view_projection = light_view_projection(frame);
  target.width = frame.params.dims[0];
  target.height = frame.params.dims[1];
  target.kind_mask = kind_mask;
  return target;
}

}  // namespace

glm::mat4 light_view_projection(const LightFrame& frame) {
  const ShadowFrame& p = frame.params;
  const float dx = float(p.dims[0]), dy = float(p.dims[1]), dz = float(p.dims[2]);
  // to_light as a 4x4 (column-major): q = A x + b.
  glm::mat4 to_light(1.0f);
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) to_light[c][r] = p.to_light[4 * r + c];
    to_light[3][r] = p.to_light[4 * r + 3];
  }
  glm::mat4 m(0.0f);  // light space (grid units or view) -> clip
  if (!frame.projective()) {
    m[0][0] = 2.0f / dx;
    m[3][0] = -1.0f;
    m[1][1] = 2.0f / dy;
    m[3][1] = -1.0f;
    m[2][2] = 1.0f / dz;
    m[3][3] = 1.0f;
  } else {
    // x_ndc = 2 (q.x / q.z - u0) inv_du / dx - 1, likewise y; z_ndc = (inv_near - 1 / q.z) depth_scale / dz.
    m[0][0] = 2.0f * p.inv_du / dx;
    m[2][0] = -(2.0f * p.u0 * p.inv_du / dx + 1.0f);
    m[1][1] = 2.0f * p.inv_dv / dy;
    m[2][1] = -(2.0f * p.v0 * p.inv_dv / dy + 1.0f);
    m[2][2] = p.inv_near * p.depth_scale / dz;
    m[3][2] = -p.depth_scale / dz;
    m[2][3] = 1.0f;
  }
  return m * to_light;
}

LightSpaceMaps::LightSpaceMaps(ClRuntime& cl) : cl_(cl), rasterizer_(cl) {}

std::vector<ProgramSpec> LightSpaceMaps::programs() const {
  return {{"shadow_filter.cl", {}}};
}

const cl::Buffer& LightSpaceMaps::opaque_depth(const DeviceMesh& mesh, const LightFrame& frame,
                                               const cl::Buffer& materials, uint32_t material_count) {
  rasterizer_.bin(mesh, light_target(frame, kOpaqueKinds), materials, material_count, opaque_bins_);
  rasterizer_.rasterize_depth(opaque_bins_, depth_);
  return depth_.buffer;
}

void LightSpaceMaps::build(const DeviceMesh& mesh, const LightFrame& frame, const RenderLight& light,
                           const cl::Buffer& materials, uint32_t material_count, ShadowMethod method) {
  VOXR_CHECK(method == ShadowMethod::kOpaque || method == ShadowMethod::kFilter);
  frame_ = frame;
  method_ = method;
  RasterTarget target = light_target(frame, method == ShadowMethod::kOpaque ? kAllKinds : kOpaqueKinds);
  rasterizer_.bin(mesh, target, materials, material_count, opaque_bins_);
  rasterizer_.rasterize_depth(opaque_bins_, depth_);
  if (method != ShadowMethod::kFilter) return;
  const uint64_t texels = uint64_t(target.width) * target.height;
  cl::Buffer& tau = optical_depth_.ensure(cl_, texels * 3 * 4, "filter optical depth map");
  cl_.fill_zero(tau, texels * 3 * 4, "clear filter map");
  target.kind_mask = kTransparentKinds;
  rasterizer_.bin(mesh, target, materials, material_count, transparent_bins_);
  cl::Kernel kernel = cl_.kernel("shadow_filter.cl", "shadow_filter_accumulate");
  rasterizer_.for_each_batch(transparent_bins_, [&](const cl::Buffer& records, uint32_t count) {
    cl_.launch("shadow_filter_accumulate", kernel, count, kGroup, frame.params, light,
               transparent_bins_.prims(), records, cl_uint(count), mesh.positions(), mesh.triangles(),
               materials, cl_uint(material_count), tau);
  });
}

void LightSpaceMaps::lookup(const cl::Buffer& samples, uint32_t count, const cl::Buffer& materials,
                            uint32_t material_count, const RenderLight& light, float bias,
                            float normal_offset, cl::Buffer& transmittance) {
  cl::Kernel kernel = cl_.kernel("shadow_filter.cl", "shadow_map_lookup");
  const cl_uint filter = method_ == ShadowMethod::kFilter ? 1 : 0;
  const cl::Buffer& tau = filter ? optical_depth_.buffer : depth_.buffer;
  cl_.launch("shadow_map_lookup", kernel, count, kGroup, samples, cl_uint(count), materials,
             cl_uint(material_count), light, frame_.params, depth_.buffer, tau, filter, bias, normal_offset,
             transmittance);
}

}  // namespace voxr
