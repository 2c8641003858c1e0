// The render side's seam, the same shape as the Voxelizer's (voxelize/voxelizer.h): a frame is one shadow
// technique and one refraction technique, each an entry of a registry (kShadowTechniques,
// kRefractionTechniques: one factory per row of the name tables kShadowMethods / kRefractionMethods, which
// stay the one source of names) behind one interface:
//   programs     what it builds before anything is timed;
//   set_scene    per-scene setup (image-space's d_N, distance maps' reference point, the voxel scene);
//   build/trace  per frame: the shadow technique's light-space structure (build), the refraction
//                technique's path ends (trace), then the shadow technique's transmittance at those ends
//                (lookup);
//   device_bytes and describe  for reports and the console.
// Every technique gets the same FrameContext from FrameRenderer: the device mesh, vertex normals, materials
// (buffer, count, host copy), camera, light, environment, the primary samples, and the exact reference
// (SceneReference, built on first need). Each technique lives in its own file, render/techniques/*.cpp.
#pragma once

#include <glm/glm.hpp>

#include <array>
#include <cstdint>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "cl/cl_runtime.h"
#include "core/grid_spec.h"
#include "core/material.h"
#include "core/triangle_soup.h"
#include "render/camera_frame.h"
#include "render/dielectric_pixels.h"
#include "render/environment_map.h"
#include "render/light_frame.h"
#include "render/refraction_method.h"
#include "render/scene_reference.h"
#include "render/shadow_method.h"
#include "util/image_rgba.h"
#include "voxelize/device_mesh.h"
#include "voxelize/raster_mode.h"

namespace voxr {

class Voxelizer;
class TriangleGrids;

struct RenderOptions {
  ShadowMethod shadows = ShadowMethod::kVoxel;
  uint32_t shadow_resolution = 256;       // columns along the longer side of the light's grid (and its slabs)
  RasterMode mode = RasterMode::kCenter;  // voxel: the light voxelizer's rule
  float bias = kDefaultShadowBias;        // slabs (or depth-map texels) towards the light
  float normal_offset = kDefaultNormalOffset;  // columns off the receiver's surface
  RefractionOptions refraction;
  bool keep_samples = false;  // read back the samples, their transmittance and the paths too
};

struct FrameStats {
  LightFrame light;                        // the light's grid (voxel, uniform, filter, opaque)
  std::map<std::string, double> stage_ms;  // profiled kernel time by stage; host references add theirs
  double host_ms = 0.0;                    // host work inside the frame: fitting, projecting, the reference
  double frame_ms = 0.0;                   // wall time of render(), from its start to the image on the host
  uint64_t host_syncs = 0;                 // waits for the device queue inside render() (ClRuntime::syncs)
  uint64_t device_bytes = 0;               // the shadow technique's grid or maps
  uint64_t light_triangles = 0;            // triangles voxelized or rasterized from the light
  GridSpec refraction_grid;                // voxel refraction: the fine grid (or the whole scene's)
  std::optional<GridSpec> refraction_coarse_grid;  // voxel refraction's coarse grid, when it has one
  uint64_t refraction_coarse_bytes = 0;            // of refraction_bytes, the coarse grid's
  uint64_t refraction_bytes = 0;    // the refraction technique's structure: the voxel grid's channels, the
                                    // image-space buffers or the distance-map layers
  uint64_t capacity_rerenders = 0;  // tries render() made again: a count outgrew the capacity kept for it
};

// What a technique says about itself after a frame: `suffix` completes the CLI's "shadows <name>" /
// "refraction <name>" line (empty: nothing to add), `lines` are further console lines (e.g. the light grid),
// `report` holds the fields it adds to the report JSON (e.g. light_grid, refraction_grid,
// refraction_options).
struct TechniqueDescription {
  std::string suffix;
  std::vector<std::string> lines;
  nlohmann::json report = nlohmann::json::object();
};

// Everything a technique may read, the same for both families. Scene members are valid from set_scene on;
// frame members (camera, light, primary_samples, pixels, stats) only inside a frame.
struct FrameContext {
  ClRuntime* cl = nullptr;
  const TriangleSoup* soup = nullptr;          // the scene's triangles, anchor-relative
  const DeviceMesh* mesh = nullptr;            // the soup on the device: the scene's one device copy
  const cl::Buffer* vertex_normals = nullptr;  // one float4 per soup vertex (render/vertex_normals.h)
  const std::vector<glm::vec3>* host_normals = nullptr;  // the same on the host
  const cl::Buffer* materials = nullptr;                 // material_count RenderMaterial
  uint32_t material_count = 0;
  const std::vector<Material>* host_materials = nullptr;
  const EnvironmentMap* environment = nullptr;  // what rays leaving the scene see (host copy)
  SceneReference* reference = nullptr;          // the exact reference; null when the caller gave none
  // The frame's per-voxel triangle lists of *mesh by resolution (render/triangle_grid.h), built on a
  // technique's first get() of each frame and shared by the exact techniques; FrameRenderer owns them.
  TriangleGrids* triangle_grids = nullptr;
  const CameraFrame* camera = nullptr;
  const RenderLight* light = nullptr;
  const cl::Buffer* primary_samples = nullptr;   // one SurfaceSample per pixel, row 0 at the top
  const DielectricPixels* dielectric = nullptr;  // the pixels whose primary sample is a dielectric (trace)
  uint64_t pixels = 0;                           // camera->width * camera->height
  FrameStats* stats = nullptr;                   // the frame's stats: techniques fill their fields, host_ms

  // The reference, or voxr::Error "<who> needs the exact reference scene (FrameRenderer::set_scene)".
  SceneReference& need_reference(const char* who) const;
};

// The light grid of a frame (stats.light, light_triangles, device_bytes) as the light-space techniques
// describe it: report "light_grid" {kind, dims, describe, triangles, device_bytes} and one console line.
TechniqueDescription light_grid_description(const FrameStats& stats);

// A technique's result on the host, when it renders the finished frame there (reference-full's reflection
// tree does not reduce to one path per pixel): image, ends, paths and the exact transmittance, per pixel.
struct HostFrame {
  ImageRgba image;
  std::vector<SurfaceSample> ends;
  std::vector<RefractionPath> paths;
  std::vector<glm::vec3> transmittance;
};

class ShadowTechnique {
 public:
  virtual ~ShadowTechnique() = default;
  // The programs a frame with `options` runs (built together with the frame's other programs).
  virtual std::vector<ProgramSpec> programs(const RenderOptions& options) const = 0;
  // Builds what programs() cannot name (e.g. the light voxelizer's own programs).
  virtual void prepare(const RenderOptions&) {}
  // Per-scene setup (scene members of `ctx`).
  virtual void set_scene(const FrameContext&) {}
  // Per frame, before the camera's buffers: the light-space structure.
  virtual void build(const FrameContext& ctx, const RenderOptions& options) = 0;
  // Transmittance (float4, RGB + 1) of ctx.pixels SurfaceSamples `ends` towards *ctx.light.
  virtual void lookup(const FrameContext& ctx, const RenderOptions& options, const cl::Buffer& ends,
                      cl::Buffer& transmittance) = 0;
  // Device memory of its structure after the last build (0 when it has none).
  virtual uint64_t device_bytes() const = 0;
  virtual TechniqueDescription describe(const FrameStats& stats, const RenderOptions& options) const = 0;
};

class RefractionTechnique {
 public:
  virtual ~RefractionTechnique() = default;
  virtual std::vector<ProgramSpec> programs(const RenderOptions& options) const = 0;
  virtual void prepare(const RenderOptions&) {}
  virtual void set_scene(const FrameContext&) {}
  // Whether trace() traces paths (false: every path is the identity, its end the primary sample, and the
  // frame has no refraction stage at all).
  virtual bool writes_ends() const = 0;
  // Per frame, for a scene with a dielectric: the RefractionPath and end SurfaceSample of every pixel that
  // *ctx.dielectric lists (those whose primary sample is a dielectric), into `paths` and `ends` (ctx.pixels
  // records each; other pixels' records are not written). A technique that renders the finished frame on the
  // host (finishes_on_host) writes nothing here.
  virtual void trace(const FrameContext& ctx, const RenderOptions& options, cl::Buffer& ends,
                     cl::Buffer& paths) = 0;
  // Whether the technique renders the finished frame on the host (render_on_host); the frame then runs no
  // shadow lookup and no shading of its own and needs no primary samples.
  virtual bool finishes_on_host() const { return false; }
  // finishes_on_host: the frame, shaded with the exact shadows. Throws InternalError otherwise.
  virtual HostFrame render_on_host(const FrameContext& ctx, const RenderOptions& options);
  virtual uint64_t device_bytes() const = 0;
  virtual TechniqueDescription describe(const FrameStats& stats, const RenderOptions& options) const = 0;
};

// Registry rows: the factory of each name-table row, in the tables' order (static_asserts in
// technique.cpp keep them aligned).
// A factory gets the device and the device's one Voxelizer (FrameRenderer's), which the techniques that
// voxelize share: one set of voxelizer scratch buffers per device.
struct ShadowTechniqueRow {
  ShadowMethod method;
  std::unique_ptr<ShadowTechnique> (*make)(ClRuntime& cl, Voxelizer& voxelizer);
};
struct RefractionTechniqueRow {
  RefractionMethod method;
  std::unique_ptr<RefractionTechnique> (*make)(ClRuntime& cl, Voxelizer& voxelizer);
};

// The factories, one per technique file in render/techniques/.
std::unique_ptr<ShadowTechnique> make_voxel_shadows(ClRuntime& cl, Voxelizer& voxelizer);  // voxel, uniform
std::unique_ptr<ShadowTechnique> make_light_map_shadows(ClRuntime& cl,
                                                        Voxelizer& voxelizer);  // filter, opaque
std::unique_ptr<ShadowTechnique> make_voxel_exact_shadows(ClRuntime& cl, Voxelizer& voxelizer);
std::unique_ptr<ShadowTechnique> make_reference_shadows(ClRuntime& cl, Voxelizer& voxelizer);
std::unique_ptr<ShadowTechnique> make_no_shadows(ClRuntime& cl, Voxelizer& voxelizer);
std::unique_ptr<RefractionTechnique> make_voxel_refraction(ClRuntime& cl,
                                                           Voxelizer& voxelizer);  // voxel-multi, voxel-two
std::unique_ptr<RefractionTechnique> make_voxel_exact_refraction(ClRuntime& cl, Voxelizer& voxelizer);
std::unique_ptr<RefractionTechnique> make_image_space_refraction(ClRuntime& cl, Voxelizer& voxelizer);
std::unique_ptr<RefractionTechnique> make_distance_map_refraction(ClRuntime& cl, Voxelizer& voxelizer);
std::unique_ptr<RefractionTechnique> make_reference_refraction(
    ClRuntime& cl, Voxelizer& voxelizer);  // reference, reference-full
std::unique_ptr<RefractionTechnique> make_no_refraction(ClRuntime& cl, Voxelizer& voxelizer);

inline constexpr std::array<ShadowTechniqueRow, 7> kShadowTechniques = {{
    {ShadowMethod::kVoxel, make_voxel_shadows},
    {ShadowMethod::kUniform, make_voxel_shadows},
    {ShadowMethod::kFilter, make_light_map_shadows},
    {ShadowMethod::kOpaque, make_light_map_shadows},
    {ShadowMethod::kVoxelExact, make_voxel_exact_shadows},
    {ShadowMethod::kReference, make_reference_shadows},
    {ShadowMethod::kNone, make_no_shadows},
}};
inline constexpr std::array<RefractionTechniqueRow, 8> kRefractionTechniques = {{
    {RefractionMethod::kVoxelMulti, make_voxel_refraction},
    {RefractionMethod::kVoxelTwo, make_voxel_refraction},
    {RefractionMethod::kVoxelExact, make_voxel_exact_refraction},
    {RefractionMethod::kImageSpace, make_image_space_refraction},
    {RefractionMethod::kDistanceMaps, make_distance_map_refraction},
    {RefractionMethod::kReference, make_reference_refraction},
    {RefractionMethod::kReferenceFull, make_reference_refraction},
    {RefractionMethod::kNone, make_no_refraction},
}};

// The technique of `method` (its registry row's factory).
std::unique_ptr<ShadowTechnique> make_shadow_technique(ClRuntime& cl, Voxelizer& voxelizer,
                                                       ShadowMethod method);
std::unique_ptr<RefractionTechnique> make_refraction_technique(ClRuntime& cl, Voxelizer& voxelizer,
                                                               RefractionMethod method);

}  // namespace voxr
