// The plain C++ reference of the kernel rasterizer (kernels/raster_setup.cl, raster_coverage.h,
// raster_depth.cl). Setup is the same clip, snap and depth plane in float with the same evaluation order (no
// contraction), so it is bit-exact where the device divides with correct rounding; coverage evaluates each
// edge function directly at every pixel centre of the primitive's bounding box (not the kernels' tiles and
// incremental steps), and the visibility buffer is a plain loop keeping the lowest word. Tests compare the
// device's words with it exactly.
#pragma once

#include <cstdint>
#include <vector>

#include "core/triangle_soup.h"
#include "render/visibility_rasterizer.h"
#include "voxr_layout.h"

namespace voxr {

// Triangle t of `soup` set up for `params` as raster_setup.cl does (prim.vertex_count 0 when it is not
// drawn). Returns its tile count.
uint32_t reference_raster_prim(const TriangleSoup& soup, uint32_t t, const RasterParams& params,
                               const std::vector<RenderMaterial>& materials, RasterPrim& prim);

// Whether `prim` covers the centre of pixel (x, y) (top-left rule on shared edges).
bool reference_covers(const RasterPrim& prim, uint32_t x, uint32_t y);

// z_ndc of `prim` at the centre of pixel (x, y), clamped to [0, 1] (raster_coverage.h raster_depth_at).
float reference_depth(const RasterPrim& prim, uint32_t x, uint32_t y, uint32_t width, uint32_t height);

struct ReferenceRaster {
  std::vector<uint64_t> visibility;  // width * height words, ~0 where no triangle
  std::vector<uint32_t> counts;      // 2 per pixel: front, back primitives covering it
  uint64_t records = 0;              // the tile records the kernels would make
};

// The whole view: visibility words, coverage counts and the record total.
ReferenceRaster reference_raster(const TriangleSoup& soup, const RasterTarget& target,
                                 const std::vector<RenderMaterial>& materials);

}  // namespace voxr
