// The pixels a refraction method traces: those whose primary sample is a dielectric surface
// (kernels/render/refraction/dielectric_pixels.cl). One kernel lists their indices on the device — the count stays there, no
// host synchronisation reads it — and writes every other pixel's path end (its primary sample), so the
// refraction kernels run over the list and write the listed pixels' ends and paths only. A refraction
// kernel launched with pixel_count() work items (its global size) takes the list as two parameters
// (`__global const uint* pixel_list, __global const uint* pixel_count`, refraction_path.h rp_listed_pixel):
// pass the DielectricPixels itself as that launch argument.
#pragma once

#include <cstdint>

#include "cl/cl_runtime.h"
#include "cl/scratch_buffers.h"

namespace voxr {

class DielectricPixels {
 public:
  explicit DielectricPixels(ClRuntime& cl) : cl_(cl) {}

  // The program find() runs.
  static ProgramSpec program();

  // Lists the pixels of `primary_samples` (`pixels` SurfaceSample) that see a dielectric (materials:
  // material_count RenderMaterial) and writes every other pixel's end into `end_samples` (pixels entries):
  // its primary sample.
  void find(const cl::Buffer& primary_samples, uint32_t pixels, const cl::Buffer& materials,
            uint32_t material_count, cl::Buffer& end_samples);

  // The pixels find() was given: the work items a refraction kernel over the list is launched with.
  uint32_t pixel_count() const { return pixels_; }
  // The listed indices (in no particular order) and their count, on the device.
  const cl::Buffer& list() const { return list_.buffer; }
  const cl::Buffer& count() const { return count_.buffer; }

  // ClRuntime::launch: the list and its count as two consecutive kernel parameters.
  void set_kernel_args(cl::Kernel& kernel, cl_uint& index) const;

 private:
  ClRuntime& cl_;
  GrowingBuffer list_, count_;
  uint32_t pixels_ = 0;
};

}  // namespace voxr
