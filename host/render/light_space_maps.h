// The two shadow-map baselines, rasterized from the light on the light grid's columns (one texel per column,
// host/render/light_frame.h) with the kernel rasterizer (visibility_rasterizer.h):
//   opaque  a classic depth shadow map (Williams 1978): the nearest caster of every kind blocks;
//   filter  what game engines do: a depth map of the opaque casters, and a light-space map of the summed
//           optical depth of every transparent surface (sheets: -ln t per crossing; dielectrics:
//           sigma_a x the distance between their front and back faces), accumulated order-independently with
//           integer atomics. Right for receivers below all transparent casters; wrong among them (a receiver
//           between leaves is shadowed by the leaves below it too).
// Lookups are 2x2 percentage-closer filtered, with the same bias and normal offset as the voxel methods.
#pragma once

#include <cstdint>
#include <vector>

#include "cl/cl_runtime.h"
#include "cl/scratch_buffers.h"
#include "render/light_frame.h"
#include "render/shadow_method.h"
#include "render/visibility_rasterizer.h"
#include "voxelize/device_mesh.h"

namespace voxr {

// The light's view-projection for the rasterizer: texel (x, y) of a width = dims.x, height = dims.y image is
// column (x, dims.y - 1 - y) of `frame`, and z_ndc = slab coordinate / dims.z.
glm::mat4 light_view_projection(const LightFrame& frame);

class LightSpaceMaps {
 public:
  explicit LightSpaceMaps(ClRuntime& cl);

  std::vector<ProgramSpec> programs() const;

  // Rasterizes `mesh` (the scene's, anchor-relative) from the light: method kOpaque or kFilter.
  void build(const DeviceMesh& mesh, const LightFrame& frame, const RenderLight& light,
             const cl::Buffer& materials, uint32_t material_count, ShadowMethod method);

  // The depth map of the opaque casters alone on `frame` (visibility words, texel (x, y) = column (x, dims.y
  // - 1 - y)), for TransparentShadowMap::lookup: the uniform method's opaque casters block through it where
  // they mix with transparent ones. Valid until the next build.
  const cl::Buffer& opaque_depth(const DeviceMesh& mesh, const LightFrame& frame, const cl::Buffer& materials,
                                 uint32_t material_count);

  // Transmittance (float4) of `count` SurfaceSamples, as TransparentShadowMap::lookup.
  void lookup(const cl::Buffer& samples, uint32_t count, const cl::Buffer& materials, uint32_t material_count,
              const RenderLight& light, float bias, float normal_offset, cl::Buffer& transmittance);

  uint64_t device_bytes() const { return depth_.bytes + optical_depth_.bytes; }

 private:
  ClRuntime& cl_;
  VisibilityRasterizer rasterizer_;
  RasterBins opaque_bins_, transparent_bins_;
  GrowingBuffer depth_, optical_depth_;
  LightFrame frame_;
  ShadowMethod method_ = ShadowMethod::kOpaque;
};

}  // namespace voxr
