// One `voxr render` run as a library function: what the CLI does between parsing its flags and writing the
// image (load the scene, open the device, render the frames, measure against the reference, build the
// report). `voxr render` (cli/cmd_render.cpp) and voxr::render (include/voxr/render.h, api/render_api.cpp)
// both call run_render_job, so the same settings give the same pixels and the same report.
#pragma once

#include <nlohmann/json.hpp>

#include <cstdint>
#include <functional>
#include <glm/glm.hpp>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "eval/render_error_target.h"
#include "render/refraction_method.h"
#include "render/shadow_method.h"
#include "render/technique.h"
#include "util/image_rgba.h"
#include "voxr_layout.h"

namespace voxr {

// The flags of `voxr render` (docs/cli.md) without its output files, with the same defaults.
struct RenderJob {
  std::string input;    // scene file (.json) or mesh; empty: the built-in default scene
  std::string shadows;  // --shadows; empty: kDefaultShadowMethod
  uint32_t shadow_res = 256;
  std::string mode;         // --mode; empty: center (voxel shadows only)
  glm::uvec2 size{0u, 0u};  // pixels; 0: the scene camera's
  std::string device;
  float bias = kDefaultShadowBias;
  float normal_offset = kDefaultNormalOffset;
  std::string refraction{refraction_method_info(kDefaultRefractionMethod).name};
  uint32_t res = 256;
  std::string refraction_grid = "fitted";
  uint32_t coarse_res = 0;
  std::string step = "papers";
  std::string normals = "smooth";
  float angle_threshold = 60.0f;
  uint32_t layers = 4;
  uint32_t layer_res = 128;
  uint32_t dm_depth = VOXR_PATH_MAX_EVENTS;
  uint32_t frames = 1;
  std::optional<double> error_target;  // image RMSE against the reference (render_error_target.h)
  bool grids_given = false;            // --res or --shadow-res given (refused with error_target)
  bool compare_reference = false;
  bool profile = false;  // keep the per-kernel time table (RenderJobResult::profile_table)
};

// What the caller sees while the job runs; every member may be empty.
struct RenderJobHooks {
  std::function<void(const std::string&)> status;   // "reading ...", "rendering...", "frame 2/10", ...
  std::function<void(const std::string&)> warning;  // the scene's warnings, as soon as it is read
  std::function<void(uint32_t frame, const ImageRgba&)> frame;  // each frame's image once rendered
  // --compare-reference writes its error images beside this image name (OUT.error.png ...); empty: none are
  // written and the report names none.
  std::string error_images_beside;
};

// The last frame, the report (`voxr render --report`'s object; ms.process is the job's own time) and what
// the CLI prints.
struct RenderJobResult {
  ImageRgba image;  // the last frame, linear RGBA, row 0 at the top
  nlohmann::json report;
  std::string source;  // the scene's name
  uint64_t triangles = 0;
  bool reference_only = false;  // the references finish the frame on the host
  bool animated = false;
  double fps = 0.0;
  RenderOptions options;  // as run (the grids --error-target chose, refraction dropped without glass)
  RefractionMethod asked_refraction = RefractionMethod::kNone;  // as asked
  TechniqueDescription shadow_description, refraction_description;
  FrameStats stats;                                     // the last frame's
  std::vector<double> frame_ms, pose_ms;                // per frame
  std::map<std::string, std::vector<double>> stage_ms;  // per stage, one per frame
  std::optional<RenderTargetChoice> target;             // --error-target's search
  FrameStats fixed_stats;     // --error-target: one frame on the fixed 512 grids it replaces
  std::string profile_table;  // job.profile: the per-kernel time table
};

// job's flags as renderer options. Throws voxr::Error naming the flag for an unknown method or a flag that
// does not apply.
RenderOptions render_job_options(const RenderJob& job);

// Runs the job. Throws voxr::Error for bad settings (an unknown method, a combination that does not apply,
// a missing or unreadable scene, a device that cannot be opened).
RenderJobResult run_render_job(const RenderJob& job, const RenderJobHooks& hooks = {});

}  // namespace voxr
