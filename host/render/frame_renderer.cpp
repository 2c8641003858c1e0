#include "render/frame_renderer.h"

#include <fmt/format.h>

#include <algorithm>

#include "render/render_scene.h"
#include "render/vertex_normals.h"
#include "util/clock.h"
#include "util/error.h"

namespace voxr {

namespace {

constexpr size_t kGroup = 64;

}  // namespace

FrameRenderer::FrameRenderer(ClRuntime& cl)
    : cl_(cl), rasterizer_(cl), dielectric_pixels_(cl), voxelizer_(cl), triangle_grids_(cl, voxelizer_) {
  ctx_.cl = &cl;
  ctx_.triangle_grids = &triangle_grids_;
}
FrameRenderer::~FrameRenderer() = default;

ShadowTechnique& FrameRenderer::shadow(ShadowMethod method) {
  std::unique_ptr<ShadowTechnique>& t = shadows_[method];
  if (!t) t = make_shadow_technique(cl_, voxelizer_, method);
  return *t;
}

RefractionTechnique& FrameRenderer::refraction(RefractionMethod method) {
  std::unique_ptr<RefractionTechnique>& t = refractions_[method];
  if (!t) t = make_refraction_technique(cl_, voxelizer_, method);
  return *t;
}

const ShadowTechnique& FrameRenderer::shadow_technique(ShadowMethod method) const {
  const auto it = shadows_.find(method);
  if (it == shadows_.end()) throw InternalError("a shadow technique this renderer has not made");
  return *it->second;
}

const RefractionTechnique& FrameRenderer::refraction_technique(RefractionMethod method) const {
  const auto it = refractions_.find(method);
  if (it == refractions_.end()) throw InternalError("a refraction technique this renderer has not made");
  return *it->second;
}

template <class Technique>
void FrameRenderer::ensure_scene(Technique& technique) {
  if (soup_ == nullptr) return;
  bool& done = scene_set_[&technique];
  if (done) return;
  technique.set_scene(ctx_);
  done = true;
}

void FrameRenderer::prepare(const RenderOptions& options) {
  ShadowTechnique& s = shadow(options.shadows);
  RefractionTechnique& r = refraction(options.refraction.method);
  std::vector<ProgramSpec> specs = rasterizer_.programs();
  for (const ProgramSpec& p : s.programs(options)) specs.push_back(p);
  for (const ProgramSpec& p : r.programs(options)) specs.push_back(p);
  specs.push_back({"shade.cl", {}});
  specs.push_back({"refract_none.cl", {}});  // keep_samples: every pixel's identity path
  if (r.writes_ends()) specs.push_back(DielectricPixels::program());
  cl_.build_programs(specs);
  s.prepare(options);
  r.prepare(options);
}

void FrameRenderer::set_environment(const EnvironmentMap& environment) {
  upload_environment(environment);
  environment_given_ = true;
}

void FrameRenderer::upload_environment(const EnvironmentMap& environment) {
  const size_t bytes = environment.pixels().size() * sizeof(glm::vec4);
  environment_ = cl_.buffer(bytes, "environment");
  cl_.upload(environment_, environment.pixels().data(), bytes, "upload environment");
  environment_size_ = {environment.width(), environment.height()};
  environment_map_ = environment;
}

void FrameRenderer::set_scene(const TriangleSoup& soup, const std::vector<Material>& materials,
                              SceneReference* reference) {
  if (materials.empty()) fail("the scene has no materials");
  for (size_t t = 0; t < soup.triangles.size(); ++t)
    if (soup.triangles[t].w >= materials.size())
      fail("triangle {} has material id {}, but the scene has {} materials", t, soup.triangles[t].w,
           materials.size());
  soup_ = &soup;
  materials_ = materials;
  mesh_ = std::make_unique<DeviceMesh>(cl_, soup);
  scene_has_dielectric_ = has_dielectric(soup, materials);
  const std::vector<RenderMaterial> mats = render_materials(materials);
  materials_buffer_ = cl_.buffer(mats.size() * sizeof(RenderMaterial), "materials");
  cl_.upload(materials_buffer_, mats.data(), mats.size() * sizeof(RenderMaterial), "upload materials");
  host_normals_ = vertex_normals(soup);
  vertex_normals_ = upload_vertex_normals(cl_, host_normals_);
  ctx_.soup = soup_;
  ctx_.mesh = mesh_.get();
  ctx_.vertex_normals = &vertex_normals_;
  ctx_.host_normals = &host_normals_;
  ctx_.materials = &materials_buffer_;
  ctx_.material_count = uint32_t(materials.size());
  ctx_.host_materials = &materials_;
  ctx_.reference = reference;
  scene_set_.clear();
  for (auto& [method, t] : shadows_) ensure_scene(*t);
  for (auto& [method, t] : refractions_) ensure_scene(*t);
}

RenderedFrame FrameRenderer::render(const RenderLight& light, const CameraFrame& camera,
                                    const RenderOptions& options, FrameStats* stats) {
  // The frame's small counts travel with its last wait (ClRuntime::set_counts_deferred): its stages run over
  // capacities kept from the frames before. A frame whose counts outgrew them (a first frame of a bigger
  // view, scene or light grid) is rendered again over the grown capacities; a count that decides the next
  // one (the large-triangle list, then its copy records) can take a second time.
  constexpr uint32_t kMostRerenders = 4;
  const auto start = Clock::now();
  const uint64_t syncs_before = cl_.syncs();
  FrameStats local;
  FrameStats& st = stats ? *stats : local;
  struct Deferral {
    ClRuntime& cl;
    ~Deferral() {
      cl.set_counts_deferred(false);
      cl.discard_counts();  // after a failure: counts still in flight
    }
  } deferral{cl_};
  cl_.set_counts_deferred(true);
  for (uint32_t rerenders = 0;; ++rerenders) {
    VOXR_CHECK_LE(rerenders, kMostRerenders);
    RenderedFrame frame = render_once(light, camera, options, st);
    if (cl_.settle_counts()) {
      st.capacity_rerenders = rerenders;
      st.frame_ms = ms_since(start);
      st.host_syncs = cl_.syncs() - syncs_before;
      return frame;
    }
  }
}

RenderedFrame FrameRenderer::render_once(const RenderLight& light, const CameraFrame& camera,
                                         const RenderOptions& options, FrameStats& st) {
  VOXR_CHECK(mesh_ != nullptr);
  st = FrameStats{};
  const auto profiled_before = cl_.profiler().stats();
  triangle_grids_.begin_frame();  // nothing precomputed: the lists are rebuilt on their first use

  ShadowTechnique& shadows = shadow(options.shadows);
  RefractionTechnique& refract = refraction(options.refraction.method);
  const glm::vec3 ambient(light.ambient[0], light.ambient[1], light.ambient[2]);
  if (!environment_given_ && (!environment_map_ || ambient_ != ambient)) {
    upload_environment(EnvironmentMap::constant(ambient));  // the light's ambient colour, when it changes
    ambient_ = ambient;
  }
  const uint64_t pixels = uint64_t(camera.width) * camera.height;
  ctx_.environment = &*environment_map_;
  ctx_.camera = &camera;
  ctx_.light = &light;
  ctx_.pixels = pixels;
  ctx_.stats = &st;
  ctx_.primary_samples = &samples_.buffer;
  ensure_scene(shadows);
  ensure_scene(refract);

  RenderedFrame frame;
  if (refract.finishes_on_host()) {
    if (options.shadows != ShadowMethod::kReference)
      fail("the {} refraction traces exact shadows; --shadows {} does not apply",
           refraction_method_info(options.refraction.method).name, shadow_method_info(options.shadows).name);
    HostFrame host = refract.render_on_host(ctx_, options);
    frame.image = std::move(host.image);
    if (options.keep_samples) {
      frame.samples = std::move(host.ends);
      frame.paths = std::move(host.paths);
      frame.transmittance = std::move(host.transmittance);
    }
  } else {
    // The per-pixel buffers grow with the image alone: a size beyond the device's largest buffer is refused
    // naming --size (cl_runtime's generic advice, a smaller --res, would not help).
    const bool any_paths = (refract.writes_ends() && scene_has_dielectric_) || options.keep_samples;
    const uint64_t per_pixel =
        std::max<uint64_t>(sizeof(SurfaceSample), any_paths ? sizeof(RefractionPath) : 0);
    if (pixels * per_pixel > cl_.device().max_allocation)
      fail(
          "a {}x{} image needs {:.1f} MiB for its per-pixel {} but the largest buffer {} allows is {:.1f} "
          "MiB; "
          "use a smaller --size",
          camera.width, camera.height, double(pixels * per_pixel) / (1 << 20),
          per_pixel == sizeof(SurfaceSample) ? "surface samples" : "refraction paths", cl_.device().name,
          double(cl_.device().max_allocation) / (1 << 20));
    // The shadow technique's light-space structure first: it does not depend on the camera's buffers.
    shadows.build(ctx_, options);

    // The camera's visibility buffer and what each pixel sees.
    rasterizer_.rasterize(*mesh_, camera_target(camera), materials_buffer_, ctx_.material_count, visibility_);
    rasterizer_.resolve(*mesh_, vertex_normals_, camera, visibility_.buffer, samples_);
    ctx_.primary_samples = &samples_.buffer;

    // Where each pixel's path through the dielectrics ends: the shadows are looked up and shading is done
    // there. Only the pixels that see a dielectric are traced; every other pixel's path is the identity and
    // its end the primary sample. Without refraction, or with no dielectric in the scene, there is no
    // refraction stage and no path buffer: the ends are the primary samples.
    const bool refracts = refract.writes_ends() && scene_has_dielectric_;
    const cl::Buffer* ends = &samples_.buffer;
    cl::Buffer* paths = nullptr;
    if (refracts || options.keep_samples)
      paths = &paths_.ensure(cl_, pixels * sizeof(RefractionPath), "refraction paths");
    if (options.keep_samples) {  // every pixel's path read back: the identity where no refraction writes one
      cl::Kernel identity = cl_.kernel("refract_none.cl", "identity_paths");
      cl_.launch("identity paths", identity, pixels, kGroup, make_render_camera(camera), *paths);
    }
    if (refracts) {
      cl::Buffer& e = ends_.ensure(cl_, pixels * sizeof(SurfaceSample), "refraction ends");
      dielectric_pixels_.find(samples_.buffer, uint32_t(pixels), materials_buffer_, ctx_.material_count, e);
      ctx_.dielectric = &dielectric_pixels_;
      refract.trace(ctx_, options, e, *paths);
      ends = &e;
    }

    cl::Buffer& transmittance = transmittance_.ensure(cl_, pixels * 16, "transmittance");
    shadows.lookup(ctx_, options, *ends, transmittance);

    cl::Buffer& image = image_.ensure(cl_, pixels * 16, "image");
    const RenderCamera render_camera = make_render_camera(camera);
    if (refracts) {
      cl::Kernel shade = cl_.kernel("shade.cl", "shade");
      cl_.launch("shade", shade, pixels, kGroup, render_camera, samples_.buffer, *ends, *paths, transmittance,
                 materials_buffer_, cl_uint(ctx_.material_count), light, environment_,
                 cl_uint(environment_size_.x), cl_uint(environment_size_.y), image);
    } else {
      cl::Kernel shade = cl_.kernel("shade.cl", "shade_primary");
      cl_.launch("shade", shade, pixels, kGroup, render_camera, samples_.buffer, transmittance,
                 materials_buffer_, cl_uint(ctx_.material_count), light, environment_,
                 cl_uint(environment_size_.x), cl_uint(environment_size_.y), image);
    }
    // Everything read back travels with the frame's one last wait.
    frame.image = ImageRgba(camera.width, camera.height);
    cl_.download_later(image, frame.image.pixels.data(), pixels * 16, "download image");
    std::vector<glm::vec4> t4;
    if (options.keep_samples) {
      frame.samples.resize(pixels);
      cl_.download_later(*ends, frame.samples.data(), pixels * sizeof(SurfaceSample), "download samples");
      frame.paths.resize(pixels);
      cl_.download_later(*paths, frame.paths.data(), pixels * sizeof(RefractionPath), "download paths");
      t4.resize(pixels);
      cl_.download_later(transmittance, t4.data(), pixels * 16, "download transmittance");
    }
    cl_.finish("rendering a frame");
    frame.transmittance.resize(t4.size());
    for (size_t i = 0; i < t4.size(); ++i) frame.transmittance[i] = glm::vec3(t4[i]);
  }
  ctx_.camera = nullptr;
  ctx_.dielectric = nullptr;
  ctx_.light = nullptr;
  ctx_.stats = nullptr;
  const Profiler::Split split = cl_.profiler().since(profiled_before);
  for (const auto& [name, ms] : split.stage_ms) st.stage_ms[name] = ms;
  st.stage_ms["upload"] = split.upload_ms;
  st.stage_ms["readback"] = split.readback_ms;
  return frame;
}

}  // namespace voxr
