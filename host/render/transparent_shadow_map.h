// Transparent shadow maps from a light-space voxel grid (kernels/shadow_transmittance.cl,
// kernels/shadow_lookup.cl): voxelize the casters from the light (the slicing axis along the light), turn
// each column into transmittance by a prefix pass, look it up at each receiver. Two methods share it:
//   voxel    Chang & Lai (TR 1688 §4.1, PG 2011 §4): per-voxel optical depth from the write count and the
//            writers' material; centre mode makes each column's count the number of surface crossings of
//            its centre ray, conservative mode over-counts.
//   uniform  Eisemann & Decoret (I3D 2006 §5): slicemap occupancy x one absorption constant.
// Everything stays on the device; nothing is read back between voxelizing and the lookup.
#pragma once

#include <glm/glm.hpp>

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "cl/cl_runtime.h"
#include "cl/scratch_buffers.h"
#include "core/material.h"
#include "core/triangle_soup.h"
#include "grid/device_voxel_grid.h"
#include "render/light_frame.h"
#include "render/shadow_method.h"
#include "voxelize/device_mesh.h"
#include "voxelize/raster_mode.h"
#include "voxelize/voxelizer.h"

namespace voxr {

struct ShadowMapOptions {
  ShadowMethod method = ShadowMethod::kVoxel;  // kVoxel or kUniform
  RasterMode mode = RasterMode::kCenter;       // voxel: the voxelizer's rule
  // Lookups move each receiver `bias` slabs towards the light and `normal_offset` columns off its surface:
  // the receiver's own crossing must not shadow it (acne); too much lets near casters' light leak through.
  float bias = kDefaultShadowBias;
  float normal_offset = kDefaultNormalOffset;
};

// The uniform method's one absorption constant (Eisemann & Decoret I3D 2006 §5): the mean per-crossing
// optical depth of the scene's transparent triangles (sheet: -ln transmittance; dielectric: sigma_a x one
// voxel of the light grid), RGB, from sums taken once per scene before the light grid's voxel length is
// known. Opaque triangles are not in the mean.
struct UniformAbsorption {
  glm::dvec3 sheet_depth{0.0};  // sum of -ln transmittance over sheet triangles
  glm::dvec3 absorption{0.0};   // sum of sigma_a over dielectric triangles
  uint64_t triangles = 0;       // transparent triangles
  uint64_t opaque = 0;          // opaque triangles
  // The mean per-crossing optical depth with dielectrics `voxel_length` thick.
  glm::vec3 at(float voxel_length) const;
  // Whether the slicemap's voxels all block (Eisemann & Decoret's opaque case): opaque triangles and no
  // transparent one. A slicemap cannot tell opaque voxels from transparent ones: where the kinds mix
  // (mixed()), the opaque casters block through a depth map of their own (TransparentShadowMap::lookup).
  bool blocks() const { return triangles == 0 && opaque > 0; }
  bool mixed() const { return triangles > 0 && opaque > 0; }
};
UniformAbsorption uniform_absorption(const TriangleSoup& soup, const std::vector<Material>& materials);

class TransparentShadowMap {
 public:
  // Voxelizes with `voxelizer` (the device's one, shared with the other techniques: one set of scratch
  // buffers).
  TransparentShadowMap(ClRuntime& cl, Voxelizer& voxelizer);

  // Builds (or loads) the voxelizer's and the shadow kernels' programs for `options`.
  void prepare(const ShadowMapOptions& options);

  // Voxelizes `light_mesh` on frame.grid (directional: the scene's mesh; point: project_to_light_grid's)
  // and fills the transmittance volume. `materials` holds material_count RenderMaterials; uniform_tau is
  // the uniform method's optical depth per occupied voxel (UniformAbsorption::at), unless uniform_blocks
  // (UniformAbsorption::blocks: the casters are all opaque), where every occupied voxel blocks, as in
  // Eisemann & Decoret's opaque case. stage_ms gains the profiled kernel time of each stage.
  void build(const DeviceMesh& light_mesh, const LightFrame& frame, const cl::Buffer& materials,
             uint32_t material_count, const glm::vec3& uniform_tau, bool uniform_blocks,
             const ShadowMapOptions& options, VoxelizeStats* stats = nullptr);

  // Transmittance (float4, RGB + 1) of `count` SurfaceSamples towards `light`: 1 where a sample has no
  // triangle or shows a dielectric. `opaque_depth`: a depth map of the opaque casters on the same frame
  // (LightSpaceMaps::opaque_depth), which then block too (uniform where opaque and transparent casters mix).
  void lookup(const cl::Buffer& samples, uint32_t count, const cl::Buffer& materials, uint32_t material_count,
              const RenderLight& light, const ShadowMapOptions& options, cl::Buffer& transmittance,
              const cl::Buffer* opaque_depth = nullptr);

  const DeviceVoxelGrid& grid() const { return grid_; }
  uint64_t device_bytes() const;  // the grid's channels and the transmittance volume

 private:
  ClRuntime& cl_;
  Voxelizer& voxelizer_;
  DeviceVoxelGrid grid_;
  GrowingBuffer volume_, tails_;  // transmittance per slab up to each column's last change; the rest
  LightFrame frame_;
};

}  // namespace voxr
