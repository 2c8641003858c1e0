// The voxel shadows keep their light grid and light mesh, the light-map shadows their light grid, while the
// scene, the light's position or direction, the camera's view and the resolution stay the same
// (render/techniques/voxel_shadows.cpp, light_map_shadows.cpp): a kept frame reads nothing back for them and
// gives the image a fresh renderer gives; a moved light or camera rebuilds them.
#include <gtest/gtest.h>

#include <cmath>

#include "core/default_scene.h"
#include "render/environment_map.h"
#include "render/frame_renderer.h"
#include "render/render_scene.h"
#include "test_support.h"

namespace voxr {
namespace {

struct DefaultScene {
  std::vector<Material> materials;
  TriangleSoup soup;
  EnvironmentMap environment = EnvironmentMap::constant(glm::vec3(0.5f));
  Scene scene = default_scene();

  DefaultScene() {
    materials = scene.materials;
    soup = take_scene_triangles(scene);
    environment = make_environment_map(scene.environment);
  }
  CameraFrame camera(float turn) const {
    Camera c = scene.camera;
    const float cs = std::cos(turn), sn = std::sin(turn);
    const glm::dvec3 d = c.position - c.look_at;
    c.position = c.look_at + glm::dvec3(cs * d.x + sn * d.z, d.y, -sn * d.x + cs * d.z);
    return make_camera_frame(c, soup.anchor, soup.bounds(), 80, 60);
  }
  RenderLight light(float dx) const {
    Light l = scene.light;
    if (l.type == "directional")  // only what the light's kind reads
      l.direction.x += dx;
    else
      l.position.x += dx;
    return render_light(l, environment.mean(), soup.anchor);
  }
};

RenderOptions options(ShadowMethod method) {
  RenderOptions o;
  o.shadows = method;
  o.shadow_resolution = 64;
  o.refraction.method = RefractionMethod::kNone;
  return o;
}

// One frame of a renderer made for it alone.
ImageRgba fresh(const DefaultScene& s, const RenderLight& light, const CameraFrame& camera, ShadowMethod m) {
  FrameRenderer r(test::runtime());
  r.set_scene(s.soup, s.materials);
  r.set_environment(s.environment);
  r.prepare(options(m));
  return r.render(light, camera, options(m)).image;
}

TEST(LightMeshReuse, KeptAndRebuiltFramesEqualFreshOnes) {
  const DefaultScene s;
  for (ShadowMethod m :
       {ShadowMethod::kVoxel, ShadowMethod::kUniform, ShadowMethod::kFilter, ShadowMethod::kOpaque}) {
    const bool voxels = m == ShadowMethod::kVoxel || m == ShadowMethod::kUniform;
    FrameRenderer r(test::runtime());
    r.set_scene(s.soup, s.materials);
    r.set_environment(s.environment);
    r.prepare(options(m));
    FrameStats first, kept;
    const ImageRgba a = r.render(s.light(0.0f), s.camera(0.0f), options(m), &first).image;
    const ImageRgba b = r.render(s.light(0.0f), s.camera(0.0f), options(m), &kept).image;
    EXPECT_EQ(a.pixels, b.pixels);
    // The kept frame fits no light frame (one wait fewer: the fit's readback) and the voxel methods build no
    // light mesh (one more: its readback).
    EXPECT_LE(kept.host_syncs + (voxels ? 2 : 1), first.host_syncs) << shadow_method_info(m).name;
    EXPECT_EQ(kept.light.grid.dims, first.light.grid.dims);
    // A moved light, then a turned camera: rebuilt, the same as a renderer that never saw the old frames.
    EXPECT_EQ(r.render(s.light(0.7f), s.camera(0.0f), options(m)).image.pixels,
              fresh(s, s.light(0.7f), s.camera(0.0f), m).pixels);
    const ImageRgba turned = r.render(s.light(0.7f), s.camera(0.4f), options(m)).image;
    EXPECT_EQ(turned.pixels, fresh(s, s.light(0.7f), s.camera(0.4f), m).pixels);
    EXPECT_NE(turned.pixels, a.pixels);
  }
}

}  // namespace
}  // namespace voxr
