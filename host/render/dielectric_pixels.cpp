#include "render/dielectric_pixels.h"

#include "util/error.h"

namespace voxr {

namespace {
constexpr size_t kGroup = 64;
}

ProgramSpec DielectricPixels::program() {
  return {"dielectric_pixels.cl", {}};
}

void DielectricPixels::find(const cl::Buffer& primary_samples, uint32_t pixels, const cl::Buffer& materials,
                            uint32_t material_count, cl::Buffer& end_samples) {
  VOXR_CHECK(material_count > 0);
  pixels_ = pixels;
  cl::Buffer& list = list_.ensure(cl_, uint64_t(pixels) * sizeof(cl_uint), "dielectric pixels");
  cl::Buffer& count = count_.ensure(cl_, sizeof(cl_uint), "dielectric pixel count");
  cl_.fill_zero(count, sizeof(cl_uint), "dielectric count");
  cl::Kernel kernel = cl_.kernel("dielectric_pixels.cl", "dielectric_pixels");
  cl_.launch("dielectric pixels", kernel, pixels, kGroup, primary_samples, cl_uint(pixels), materials,
             cl_uint(material_count), list, count, end_samples);
}

void DielectricPixels::set_kernel_args(cl::Kernel& kernel, cl_uint& index) const {
  kernel.setArg(index++, list_.buffer);
  kernel.setArg(index++, count_.buffer);
}

}  // namespace voxr
