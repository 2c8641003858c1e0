// The host's side of kernels/common/voxr_layout.h: every shared struct has the size the kernels assume (the
// device's own sizes and offsets are compared by tests/layout_test.cpp), and the host types that mirror
// kernel vector types have their width.
#include <glm/glm.hpp>

#include <cstddef>

#include "cl/cl_runtime.h"
#include "voxr_layout.h"

namespace voxr {

static_assert(sizeof(VoxGridParams) == 88);
static_assert(sizeof(CopyBox) == 8);
static_assert(sizeof(CopyRecord) == 8);
static_assert(sizeof(VoxSnappedTriangle) == 48);
static_assert(sizeof(VoxColorParams) == 16);
static_assert(sizeof(VoxColorLook) == 16);
static_assert(sizeof(VoxSolidLayout) == 32);
static_assert(sizeof(VoxGridView) == 80);
static_assert(sizeof(RenderMaterial) == 48);
static_assert(sizeof(RenderLight) == 64);
static_assert(sizeof(SurfaceSample) == 64);
static_assert(sizeof(RefractionPath) == 64);
static_assert(sizeof(VoxelLevelParams) == 32);
static_assert(sizeof(VoxelRefractParams) == 96);
static_assert(sizeof(ImageSpaceParams) == 16);
static_assert(sizeof(DistanceMapParams) == 48);
static_assert(sizeof(ShadowFrame) == 96);
static_assert(sizeof(LightFitParams) == 112);
static_assert(sizeof(LightPiecesParams) == 144);
static_assert(sizeof(RasterParams) == 96);
static_assert(offsetof(RasterParams, cull) == 92, "the cull flag took the former pad word");
static_assert(sizeof(RasterPrim) == 88);
static_assert(sizeof(RenderCamera) == 64);
static_assert(sizeof(glm::vec4) == sizeof(cl_float4) && sizeof(glm::uvec4) == sizeof(cl_uint4));
static_assert(sizeof(glm::ivec3) == 12 && sizeof(glm::vec3) == 12, "sparse int3/float3 channels are packed");

}  // namespace voxr
