#include "render/frame_renderer.h"

#include <fmt/format.h>

#include "core/clock.h"
#include "core/error.h"
#include "render/render_scene.h"
#include "render/vertex_normals.h"

namespace voxr {

namespace {

constexpr size_t kGroup = 64;

ShadowMapOptions shadow_map_options(const RenderOptions& o) {
  ShadowMapOptions s;
  s.method = o.shadows;
  s.mode = o.mode;
  s.bias = o.bias;
  s.normal_offset = o.normal_offset;
  return s;
}

bool uses_voxel_grid(ShadowMethod m) {
  return m == ShadowMethod::kVoxel || m == ShadowMethod::kUniform;
}
bool uses_light_maps(ShadowMethod m) {
  return m == ShadowMethod::kFilter || m == ShadowMethod::kOpaque;
}

}  // namespace

FrameRenderer::FrameRenderer(ClRuntime& cl)
    : cl_(cl),
      rasterizer_(cl),
      shadow_map_(cl),
      light_maps_(cl),
      voxel_refraction_(cl),
      image_space_(cl, rasterizer_),
      distance_maps_(cl),
      dielectric_pixels_(cl) {}
FrameRenderer::~FrameRenderer() = default;

void FrameRenderer::prepare(const RenderOptions& options) {
  std::vector<ProgramSpec> specs = rasterizer_.programs();
  if (uses_light_maps(options.shadows))
    for (const ProgramSpec& p : light_maps_.programs()) specs.push_back(p);
  if (options.refraction.method == RefractionMethod::kImageSpace)
    for (const ProgramSpec& p : image_space_.programs()) specs.push_back(p);
  if (options.refraction.method == RefractionMethod::kDistanceMaps)
    for (const ProgramSpec& p : distance_maps_.programs()) specs.push_back(p);
  if (options.refraction.method != RefractionMethod::kNone) specs.push_back(DielectricPixels::program());
  specs.push_back({"shade.cl", {}});
  specs.push_back({"refract_none.cl", {}});
  cl_.build_programs(specs);
  if (uses_voxel_grid(options.shadows)) shadow_map_.prepare(shadow_map_options(options));
  if (is_voxel_refraction(options.refraction.method)) voxel_refraction_.prepare(options.refraction);
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
}

void FrameRenderer::set_inward_distances(const std::vector<float>& d_n) {
  image_space_.set_inward_distances(d_n);
  inward_distances_set_ = true;
}

void FrameRenderer::set_scene(const TriangleSoup& soup, const std::vector<Material>& materials) {
  if (materials.empty()) fail("the scene has no materials");
  for (size_t t = 0; t < soup.triangles.size(); ++t)
    if (soup.triangles[t].w >= materials.size())
      fail("triangle {} has material id {}, but the scene has {} materials", t, soup.triangles[t].w,
           materials.size());
  soup_ = &soup;
  materials_ = materials;
  material_count_ = uint32_t(materials.size());
  mesh_ = std::make_unique<DeviceMesh>(cl_, soup);
  const std::vector<RenderMaterial> mats = render_materials(materials);
  materials_buffer_ = cl_.buffer(mats.size() * sizeof(RenderMaterial), "materials");
  cl_.upload(materials_buffer_, mats.data(), mats.size() * sizeof(RenderMaterial), "upload materials");
  vertex_normals_ = upload_vertex_normals(cl_, vertex_normals(soup));
  inward_distances_set_ = false;
  scene_has_dielectric_ = false;
  for (const glm::uvec4& t : soup.triangles)
    scene_has_dielectric_ = scene_has_dielectric_ || materials[t.w].kind == MaterialKind::kDielectric;
  voxel_refraction_.set_scene(soup);
  distance_maps_.set_scene(soup, materials);
}

RenderedFrame FrameRenderer::render(const RenderLight& light, const CameraFrame& camera,
                                    const RenderOptions& options, const HostTransmittance& host_transmittance,
                                    FrameStats* stats) {
  VOXR_CHECK(mesh_ != nullptr);
  const auto start = Clock::now();
  FrameStats local;
  FrameStats& st = stats ? *stats : local;
  st = FrameStats{};
  const auto profiled_before = cl_.profiler().stats();
  double host_ms = 0.0;

  const uint64_t pixels = uint64_t(camera.width) * camera.height;
  // The shadow method's light-space structure first: it does not depend on the camera's buffers.
  if (uses_voxel_grid(options.shadows) || uses_light_maps(options.shadows)) {
    const auto fit_start = Clock::now();
    const Bounds receivers = visible_bounds(soup_->bounds(), camera);
    st.light = fit_light_frame(light, receivers, *soup_, options.shadow_resolution);
    host_ms += ms_since(fit_start);
  }
  if (uses_voxel_grid(options.shadows)) {
    const auto host_start = Clock::now();
    TriangleSoup projected;
    if (st.light.projective()) projected = project_to_light_grid(*soup_, st.light);
    const TriangleSoup& light_soup = st.light.projective() ? projected : *soup_;
    DeviceMesh light_mesh = upload_mesh(cl_, light_soup, st.light.grid, SplitCull::kGrid);
    const glm::vec3 tau = options.shadows == ShadowMethod::kUniform
                              ? uniform_optical_depth(*soup_, materials_, st.light.mean_slab_length())
                              : glm::vec3(0.0f);
    host_ms += ms_since(host_start);
    st.light_triangles = light_mesh.triangle_count();
    shadow_map_.build(light_mesh, st.light, materials_buffer_, material_count_, tau,
                      shadow_map_options(options));
    st.device_bytes = shadow_map_.device_bytes();
  } else if (uses_light_maps(options.shadows)) {
    light_maps_.build(*mesh_, st.light, light, materials_buffer_, material_count_, options.shadows);
    st.light_triangles = mesh_->triangle_count();
    st.device_bytes = light_maps_.device_bytes();
  }

  // The camera's visibility buffer and what each pixel sees.
  rasterizer_.rasterize(*mesh_, camera_target(camera), materials_buffer_, material_count_, visibility_);
  rasterizer_.resolve(*mesh_, vertex_normals_, camera, visibility_.buffer, samples_);
  cl::Buffer& transmittance = transmittance_.ensure(cl_, pixels * 16, "transmittance");

  // Where each pixel's path through the dielectrics ends: the shadows are looked up and shading is done
  // there. Only the pixels that see a dielectric are traced; every other pixel's path is the identity and
  // its end the primary sample. Without refraction, or with no dielectric in the scene, there is no
  // refraction stage and no path buffer: the ends are the primary samples.
  const RefractionMethod refraction = options.refraction.method;
  if (refraction == RefractionMethod::kReference || refraction == RefractionMethod::kReferenceFull)
    fail("the {} refraction renders on the host (render_refraction_reference), not in a device frame",
         refraction_method_info(refraction).name);
  const bool refracts = refraction != RefractionMethod::kNone && scene_has_dielectric_;
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
    dielectric_pixels_.find(samples_.buffer, uint32_t(pixels), materials_buffer_, material_count_, e);
    switch (refraction) {
      case RefractionMethod::kVoxelMulti:
      case RefractionMethod::kVoxelTwo:
        voxel_refraction_.build(options.refraction);
        voxel_refraction_.trace(camera, samples_.buffer, dielectric_pixels_, materials_buffer_,
                                material_count_, options.refraction, e, *paths);
        st.refraction_grid = voxel_refraction_.grid().spec;
        st.refraction_bytes = voxel_refraction_.grid().device_bytes();
        break;
      case RefractionMethod::kImageSpace:
        if (!inward_distances_set_)
          fail("image-space refraction needs the inward distances (set_inward_distances)");
        image_space_.trace(*mesh_, vertex_normals_, camera, materials_buffer_, material_count_,
                           samples_.buffer, dielectric_pixels_, e, *paths);
        st.refraction_bytes = image_space_.device_bytes();
        break;
      case RefractionMethod::kDistanceMaps:
        distance_maps_.trace(*mesh_, vertex_normals_, camera, materials_buffer_, material_count_,
                             options.refraction, samples_.buffer, dielectric_pixels_, e, *paths);
        st.refraction_bytes = distance_maps_.device_bytes();
        break;
      case RefractionMethod::kNone:
      case RefractionMethod::kReference:
      case RefractionMethod::kReferenceFull:
        break;  // no device refraction: excluded above
    }
    ends = &e;
  }

  RenderedFrame frame;
  switch (options.shadows) {
    case ShadowMethod::kVoxel:
    case ShadowMethod::kUniform:
      shadow_map_.lookup(*ends, uint32_t(pixels), materials_buffer_, material_count_, light,
                         shadow_map_options(options), transmittance);
      break;
    case ShadowMethod::kFilter:
    case ShadowMethod::kOpaque:
      light_maps_.lookup(*ends, uint32_t(pixels), materials_buffer_, material_count_, light, options.bias,
                         options.normal_offset, transmittance);
      break;
    case ShadowMethod::kReference: {
      if (!host_transmittance) fail("the reference shadows need the reference renderer");
      frame.samples.resize(pixels);
      cl_.download(*ends, frame.samples.data(), pixels * sizeof(SurfaceSample), "download samples");
      cl_.finish("resolving the camera's samples");
      const auto host_start = Clock::now();
      const std::vector<glm::vec3> t = host_transmittance(frame.samples);
      host_ms += ms_since(host_start);
      std::vector<glm::vec4> t4(pixels);
      for (size_t i = 0; i < pixels; ++i) t4[i] = glm::vec4(t[i], 1.0f);
      cl_.upload(transmittance, t4.data(), pixels * 16, "upload reference transmittance");
      break;
    }
    case ShadowMethod::kNone: {
      const glm::vec4 one(1.0f);
      cl_.queue().enqueueFillBuffer(transmittance, one, 0, pixels * 16);
      break;
    }
  }

  cl::Buffer& image = image_.ensure(cl_, pixels * 16, "image");
  if (!environment_given_)  // the light's ambient colour, which may change from frame to frame
    upload_environment(
        EnvironmentMap::constant(glm::vec3(light.ambient[0], light.ambient[1], light.ambient[2])));
  const RenderCamera render_camera = make_render_camera(camera);
  if (refracts) {
    cl::Kernel shade = cl_.kernel("shade.cl", "shade");
    cl_.launch("shade", shade, pixels, kGroup, render_camera, samples_.buffer, *ends, *paths, transmittance,
               materials_buffer_, cl_uint(material_count_), light, environment_, cl_uint(environment_size_.x),
               cl_uint(environment_size_.y), image);
  } else {
    cl::Kernel shade = cl_.kernel("shade.cl", "shade_primary");
    cl_.launch("shade", shade, pixels, kGroup, render_camera, samples_.buffer, transmittance,
               materials_buffer_, cl_uint(material_count_), light, environment_, cl_uint(environment_size_.x),
               cl_uint(environment_size_.y), image);
  }
  frame.image = ImageRgba(camera.width, camera.height);
  cl_.download(image, frame.image.pixels.data(), pixels * 16, "download image");
  if (options.keep_samples) {
    if (frame.samples.empty()) {  // the reference path has them already
      frame.samples.resize(pixels);
      cl_.download(*ends, frame.samples.data(), pixels * sizeof(SurfaceSample), "download samples");
    }
    frame.paths.resize(pixels);
    cl_.download(*paths, frame.paths.data(), pixels * sizeof(RefractionPath), "download paths");
    std::vector<glm::vec4> t4(pixels);
    cl_.download(transmittance, t4.data(), pixels * 16, "download transmittance");
    cl_.finish("rendering a frame");
    frame.transmittance.resize(pixels);
    for (size_t i = 0; i < pixels; ++i) frame.transmittance[i] = glm::vec3(t4[i]);
  } else {
    cl_.finish("rendering a frame");
  }
  st.frame_ms = ms_since(start);
  st.host_ms = host_ms;
  const Profiler::Split split = cl_.profiler().since(profiled_before);
  st.stage_ms = split.stage_ms;
  st.stage_ms["upload"] = split.upload_ms;
  st.stage_ms["readback"] = split.readback_ms;
  return frame;
}

}  // namespace voxr
