// voxr's renderer as a library: one `voxr render` run (docs/cli.md, docs/library.md) returning the image and
// the report instead of writing files. A program links voxr::render (libvoxr_render, find_package(voxr));
// the Python package's voxr.render calls the same function.
//
// The same settings give the same pixels as `voxr render -o out.exr` (both run one library function). The
// image is linear RGB with alpha, row 0 at the top; the scene, camera, light and materials are the scene
// file's (docs/scene-format.md) or the built-in default scene's.
//
// Errors: voxr::render throws voxr::Error (include/voxr/error.h) with voxr's one-line message for bad input:
// an unknown method, a setting out of range or one that does not apply to the chosen method, a scene file
// that cannot be read, a device that selects nothing.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "voxr/error.h"

namespace voxr {

// What `voxr render` takes as flags, with the same names and defaults (docs/cli.md#render). Settings that
// only one method reads (mode; layers, layer_res, dm_depth) are refused with another when changed from
// their defaults, as the CLI refuses the flags.
struct RenderSettings {
  std::string scene;    // scene file (.json) or mesh; empty: the built-in default scene
  std::string shadows;  // --shadows: voxel, uniform, filter, opaque, voxel-exact, reference,
                        // none; empty: voxel (reference with a reference refraction)
  std::string refraction = "voxel-exact";  // --refraction (a scene without glass renders none)
  uint32_t width = 0, height = 0;          // --size; 0, 0: the scene camera's
  std::string device;                      // "P:D", "P", a name substring; empty: $VOXR_DEVICE or default
  uint32_t shadow_res = 256;               // --shadow-res: the light grid's columns along its longer side
  uint32_t res = 256;                      // --res: the refraction grid's voxels along its longest side
  std::string mode;                        // --mode (voxel shadows): center (empty) or conservative
  float bias = 1.5f;                       // --bias: slabs (or depth-map texels) towards the light
  float normal_offset = 0.25f;             // --normal-offset: columns off the receiver's surface
  std::string refraction_grid = "fitted";  // --refraction-grid
  uint32_t coarse_res = 0;                 // --coarse-res; 0: res / 2
  std::string step = "papers";             // --step: papers or dda
  std::string normals = "smooth";          // --normals: voxel or smooth
  float angle_threshold = 60.0f;           // --angle-threshold (voxel-multi), degrees
  uint32_t layers = 4;                     // --layers (distance-maps)
  uint32_t layer_res = 128;                // --layer-res (distance-maps)
  uint32_t dm_depth = 0;                   // --dm-depth (distance-maps); 0: the most a path may have
  uint32_t frames = 1;  // --frames: frames rendered (an animated scene's f / fps); the last is returned
  std::optional<double> error_target;  // --error-target: image RMSE chosen grids must meet (res, shadow_res
                                       // left at their defaults)
  bool compare_reference = false;      // --compare-reference: the error against the Embree reference, in
                                       // the report's compare_reference (no error image is written)
};

// One rendered image. rgba: height * width * 4 floats, pixel (x, y) at (y * width + x) * 4, row 0 = top.
struct RenderedImage {
  uint32_t width = 0, height = 0;
  std::vector<float> rgba;
  std::string report_json;            // the same object as `voxr render --report`
  std::vector<std::string> warnings;  // what the CLI prints as "voxr: warning: ..." (the scene's)
};

// Renders as `voxr render` does with the same settings. Opens the device for the call (the OpenCL program
// cache makes a second call's build a load). Throws voxr::Error as the header comment says.
VOXR_API RenderedImage render(const RenderSettings& settings = {});

}  // namespace voxr
