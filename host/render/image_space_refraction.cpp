#include "render/image_space_refraction.h"

#include <glm/glm.hpp>

#include "util/error.h"
#include "voxr_layout.h"

namespace voxr {

namespace {

constexpr size_t kGroup = 64;  // image_space.cl's PATH_GROUP

}  // namespace

ImageSpaceRefraction::ImageSpaceRefraction(ClRuntime& cl, VisibilityRasterizer& rasterizer)
    : cl_(cl), rasterizer_(rasterizer) {}

std::vector<ProgramSpec> ImageSpaceRefraction::programs() const {
  return {{"image_space.cl", {}}};
}

void ImageSpaceRefraction::set_inward_distances(const std::vector<float>& d_n) {
  inward_count_ = uint32_t(d_n.size());
  cl::Buffer& buffer = inward_distance_.ensure(cl_, d_n.size() * sizeof(float), "inward distances");
  if (!d_n.empty())  // blocking: `d_n` may go
    cl_.upload(buffer, d_n.data(), d_n.size() * sizeof(float), "upload inward distances");
}

void ImageSpaceRefraction::trace(const DeviceMesh& mesh, const cl::Buffer& vertex_normals,
                                 const CameraFrame& camera, const cl::Buffer& materials,
                                 uint32_t material_count, const cl::Buffer& primary_samples,
                                 const DielectricPixels& dielectric, cl::Buffer& end_samples,
                                 cl::Buffer& paths) {
  VOXR_CHECK(material_count > 0);
  // The dielectrics' back faces, nearest kept: d_V and the exit normals.
  RasterTarget back = camera_target(camera);
  back.kind_mask = 1u << VOXR_MATERIAL_DIELECTRIC;
  back.cull = FaceCull::kFront;
  rasterizer_.rasterize(mesh, back, materials, material_count, back_visibility_);
  rasterizer_.resolve(mesh, vertex_normals, camera, back_visibility_.buffer, back_samples_);
  // The surfaces the exit rays may see: everything but the dielectrics, both faces.
  RasterTarget opaque = camera_target(camera);
  opaque.kind_mask = (1u << VOXR_MATERIAL_OPAQUE) | (1u << VOXR_MATERIAL_SHEET);
  rasterizer_.rasterize(mesh, opaque, materials, material_count, opaque_visibility_);
  rasterizer_.resolve(mesh, vertex_normals, camera, opaque_visibility_.buffer, opaque_samples_);

  cl::Buffer& inward = inward_distance_.ensure(cl_, 4, "inward distances");  // one word when none were set
  ImageSpaceParams p{};
  p.triangle_count = mesh.triangle_count();
  p.inward_count = inward_count_;
  p.iterations = kImageSpaceIterations;
  const float size = glm::length(mesh.bounds().size());
  p.scene_size = size > 0.0f ? size : 1.0f;
  cl::Kernel kernel = cl_.kernel("image_space.cl", "image_space");
  VOXR_CHECK_EQ(uint64_t(dielectric.pixel_count()), uint64_t(camera.width) * camera.height);
  cl_.launch("refraction", kernel, dielectric.pixel_count(), kGroup, make_render_camera(camera),
             primary_samples, dielectric, back_samples_.buffer, opaque_samples_.buffer, materials,
             cl_uint(material_count), mesh.triangles(), inward, p, end_samples, paths);
}

}  // namespace voxr
