#include "render/image_space_refraction.h"

#include "core/error.h"

namespace voxr {

// Placeholder until the image-space kernels land (helper branch).
ImageSpaceRefraction::ImageSpaceRefraction(ClRuntime& cl, VisibilityRasterizer& rasterizer)
    : cl_(cl), rasterizer_(rasterizer) {}

std::vector<ProgramSpec> ImageSpaceRefraction::programs() const {
  return {};
}

void ImageSpaceRefraction::set_inward_distances(const std::vector<float>&) {}

void ImageSpaceRefraction::trace(const DeviceMesh&, const cl::Buffer&, const CameraFrame&, const cl::Buffer&,
                                 uint32_t, const cl::Buffer&, cl::Buffer&, cl::Buffer&) {
  fail("image-space refraction is not built yet");
}

}  // namespace voxr
