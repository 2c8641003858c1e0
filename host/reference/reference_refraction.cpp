#include "reference/reference_refraction.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <span>

#include "media_stack.h"
#include "reference/parallel_blocks.h"
#include "refraction.h"
#include "render/shade_host.h"
#include "util/clock.h"
#include "util/error.h"

namespace voxr {

namespace {

// Surfaces met along one path or branch at most (sheets included): a guard against rays caught between
// coincident surfaces; a path that reaches it is lost.
constexpr uint32_t kMaxSegments = 4096;
// Full model: branches whose weight (largest channel) falls below this are not traced: the interface
// limit adapts to the throughput left.
constexpr float kMinBranchWeight = 1e-3f;

glm::vec3 vec(const float* v) {
  return glm::vec3(v[0], v[1], v[2]);
}

void store(float* out, const glm::vec3& v) {
  out[0] = v.x;
  out[1] = v.y;
  out[2] = v.z;
}

// kernels/refraction_path.h rp_reflect: d mirrored about n (both unit).
glm::vec3 reflect(const glm::vec3& d, const glm::vec3& n) {
  return d - 2.0f * glm::dot(d, n) * n;
}

// kernels/refraction_path.h rp_refract, line for line: refracts unit d at a surface of unit normal n (either
// orientation) from index n1 into n2. True and the refracted direction in t, or false on total internal
// reflection (t is then the mirror direction); cos_i receives the incidence cosine.
bool refract(const glm::vec3& d, glm::vec3 n, float n1, float n2, glm::vec3& t, float& cos_i) {
  if (glm::dot(d, n) > 0.0f) n = -n;
  const float ci = std::min(-glm::dot(d, n), 1.0f);
  cos_i = ci;
  const float ct = voxr_refracted_cos(ci, n1, n2);
  if (ct < 0.0f) {
    t = reflect(d, n);
    return false;
  }
  const float eta = n1 / n2;
  t = glm::normalize(eta * d + (eta * ci - ct) * n);
  return true;
}

// kernels/refraction_path.h rp_identity.
RefractionPath identity_path(const glm::vec3& dir) {
  RefractionPath p{};
  store(p.throughput, glm::vec3(1.0f));
  p.events = 0u;
  p.fresnel = 0.0f;
  store(p.exit_direction, dir);
  return p;
}

SurfaceSample no_surface() {
  SurfaceSample s{};
  s.triangle = VOXR_NO_TRIANGLE;
  return s;
}

// The triangles a ray leaves (ReferenceScene::intersect_leaving): the one it left, and before it those met
// at the same point (a coincident surface passed within the merge distance), at most 8.
struct Leaving {
  uint32_t id[8] = {};
  uint32_t count = 0;

  explicit Leaving(uint32_t triangle) : count(1) { id[0] = triangle; }
  std::span<const uint32_t> ids() const { return {id, count}; }
  // The set after leaving `hit`, met `hit.distance` from the point left.
  Leaving after(const SurfaceSample& hit, float merge) const {
    Leaving next = *this;
    if (hit.distance <= merge && count < 8)
      next.id[next.count++] = hit.triangle;
    else
      next = Leaving(hit.triangle);
    return next;
  }
};

class Tracer {
 public:
  Tracer(const ReferenceScene& scene, const std::vector<RenderMaterial>& materials, const RenderLight& light,
         const EnvironmentMap& environment, uint32_t max_interfaces)
      : scene_(scene),
        materials_(materials),
        light_(light),
        environment_(environment),
        merge_(ReferenceScene::kMergeDistance * scene.scene_size()),
        max_interfaces_(max_interfaces) {}

  // The matched model (refract_voxel.cl's, exact triangles for voxels) for the camera ray eye + t dir.
  void matched(const glm::vec3& eye, glm::vec3 dir, SurfaceSample& end, RefractionPath& path) const {
    const SurfaceSample s = scene_.intersect(eye, dir);
    path = identity_path(dir);
    if (s.triangle == VOXR_NO_TRIANGLE || material(s.material).kind != VOXR_MATERIAL_DIELECTRIC) {
      end = s;
      return;
    }
    // The front surface: Schlick's F reflects the environment, 1 - F refracts in (with the shading normal,
    // turned towards the eye).
    const glm::vec3 n_front = vec(s.normal);
    const float n_in = material(s.material).ior;
    glm::vec3 t_dir;
    float cos_i;
    refract(dir, n_front, 1.0f, n_in, t_dir, cos_i);
    path.fresnel = voxr_schlick(cos_i, 1.0f, n_in);
    store(path.reflect_direction, reflect(dir, n_front));
    glm::vec3 throughput(1.0f - path.fresnel);
    uint32_t events = 1u;
    dir = t_dir;
    glm::vec3 here = vec(s.position), exit = here;
    VoxrMedia media = voxr_media_empty();
    voxr_media_cross(&media, s.material, 1);  // the camera is outside every medium

    end = no_surface();
    bool ended = false;
    Leaving left(s.triangle);
    for (uint32_t segment = 0;; ++segment) {
      if (segment >= kMaxSegments) {
        events |= VOXR_PATH_LOST;
        ended = true;
        break;
      }
      const SurfaceSample hit = scene_.intersect_leaving(here, dir, left.ids());
      if (hit.triangle == VOXR_NO_TRIANGLE) break;  // leaves the scene: the environment
      left = left.after(hit, merge_);
      throughput *= absorption(media, hit.distance);
      here = vec(hit.position);
      const RenderMaterial& m = material(hit.material);
      if (m.kind == VOXR_MATERIAL_OPAQUE) {
        end = hit;
        ended = true;
        break;
      }
      if (m.kind == VOXR_MATERIAL_SHEET) {
        throughput *= vec(m.transmittance);
        continue;
      }
      // A dielectric interface, entered or left by the triangle's winding (refraction_path.h rp_interface).
      const int enters = voxr_media_enters(&media, hit.material, facing(dir, hit));
      if (voxr_media_overflows(&media, hit.material, enters)) {  // nested deeper than the stack holds
        events |= VOXR_PATH_LOST;
        ended = true;
        break;
      }
      const float n1 = ior(voxr_media_top(&media));
      const float n2 = ior(voxr_media_far(&media, hit.material, enters));
      if (n1 == n2) {  // index-matched: no interface (no event), straight on
        voxr_media_cross(&media, hit.material, enters);
        exit = here;  // as the kernels record it: the last dielectric surface crossed
        continue;
      }
      glm::vec3 new_dir;
      if (refract(dir, vec(hit.normal), n1, n2, new_dir, cos_i)) {
        throughput *= 1.0f - voxr_schlick(cos_i, n1, n2);
        voxr_media_cross(&media, hit.material, enters);
      } else {
        events |= VOXR_PATH_TIR;
      }
      ++events;
      exit = here;
      if ((events & VOXR_PATH_EVENTS_MASK) >= VOXR_PATH_MAX_EVENTS) {
        events |= VOXR_PATH_LOST;
        ended = true;
        break;
      }
      dir = new_dir;
    }
    if (!ended) events |= VOXR_PATH_ENV;
    store(path.throughput, throughput);
    path.events = events;
    store(path.exit_position, exit);
    store(path.exit_direction, dir);
  }

  // The full model: radiance along origin + t dir for a ray inside `media` that leaves the triangles
  // `left` (none: the camera ray) having met `interfaces` dielectric interfaces so far, and carries
  // `weight` (its largest channel) to the pixel. The camera ray's first surface is shaded whether opaque or
  // a sheet (as the primary sample of every other method); any later ray crosses sheets, multiplied by
  // their transmittance.
  glm::vec3 full(glm::vec3 origin, const glm::vec3& dir, VoxrMedia media, uint32_t interfaces, float weight,
                 std::optional<Leaving> left) const {
    const bool camera = !left;
    glm::vec3 carried(1.0f);
    for (uint32_t segment = 0; segment < kMaxSegments; ++segment) {
      const SurfaceSample hit =
          left ? scene_.intersect_leaving(origin, dir, left->ids()) : scene_.intersect(origin, dir);
      if (hit.triangle == VOXR_NO_TRIANGLE) return carried * environment_.lookup(dir);
      const Leaving next_left = left ? left->after(hit, merge_) : Leaving(hit.triangle);
      carried *= absorption(media, hit.distance);
      const glm::vec3 here = vec(hit.position);
      const RenderMaterial& m = material(hit.material);
      if (m.kind == VOXR_MATERIAL_OPAQUE || (m.kind == VOXR_MATERIAL_SHEET && camera && segment == 0)) {
        const glm::vec3 t = scene_.transmittance(light_, here, hit.triangle);
        return carried * shade_surface_sample(hit, t, materials_, light_);
      }
      if (m.kind == VOXR_MATERIAL_SHEET) {
        carried *= vec(m.transmittance);
        origin = here;
        left = next_left;
        continue;
      }
      if (interfaces >= max_interfaces_) return glm::vec3(0.0f);  // a guard against loops only
      const int enters = voxr_media_enters(&media, hit.material, facing(dir, hit));
      if (voxr_media_overflows(&media, hit.material, enters))
        return glm::vec3(0.0f);  // nested deeper than the stack holds
      const float n1 = ior(voxr_media_top(&media));
      const float n2 = ior(voxr_media_far(&media, hit.material, enters));
      if (n1 == n2) {  // index-matched: no interface, straight on (F = 0)
        voxr_media_cross(&media, hit.material, enters);
        origin = here;
        left = next_left;
        continue;
      }
      glm::vec3 normal = vec(hit.normal);
      if (glm::dot(dir, normal) > 0.0f) normal = -normal;
      glm::vec3 t_dir;
      float cos_i;
      const bool refracted = refract(dir, normal, n1, n2, t_dir, cos_i);
      const float f = refracted ? voxr_fresnel_exact(cos_i, n1, n2) : 1.0f;
      const float w = weight * std::max({carried.x, carried.y, carried.z});
      glm::vec3 radiance(0.0f);
      if (f * w >= kMinBranchWeight)
        radiance += f * full(here, reflect(dir, normal), media, interfaces + 1, f * w, next_left);
      if (refracted && (1.0f - f) * w >= kMinBranchWeight) {
        VoxrMedia next = media;
        voxr_media_cross(&next, hit.material, enters);
        radiance += (1.0f - f) * full(here, t_dir, next, interfaces + 1, (1.0f - f) * w, next_left);
      }
      return carried * radiance;
    }
    return glm::vec3(0.0f);  // caught between surfaces: lost
  }

 private:
  const RenderMaterial& material(uint32_t id) const {
    if (id >= materials_.size())
      fail("refraction reference: a triangle has material {} but there are {} materials", id,
           materials_.size());
    return materials_[id];
  }
  // The index of refraction of a medium (a material id, or VOXR_MEDIA_AIR: 1).
  float ior(uint32_t medium) const { return medium == VOXR_MEDIA_AIR ? 1.0f : material(medium).ior; }
  // dot(dir, the hit triangle's winding normal): < 0 where the ray enters the solid (media_stack.h).
  float facing(const glm::vec3& dir, const SurfaceSample& hit) const {
    return glm::dot(dir, scene_.winding_normal(hit.triangle));
  }
  // Beer-Lambert over `length` world units inside the innermost medium (1 in air).
  glm::vec3 absorption(const VoxrMedia& media, float length) const {
    const uint32_t top = voxr_media_top(&media);
    if (top == VOXR_MEDIA_AIR) return glm::vec3(1.0f);
    const glm::vec3 sigma = vec(material(top).absorption);
    return glm::exp(-sigma * length);
  }

  const ReferenceScene& scene_;
  const std::vector<RenderMaterial>& materials_;
  const RenderLight& light_;
  const EnvironmentMap& environment_;
  float merge_;  // ReferenceScene::kMergeDistance in world units
  uint32_t max_interfaces_;
};

}  // namespace

RefractionReference render_refraction_reference(const ReferenceScene& scene,
                                                const std::vector<RenderMaterial>& materials,
                                                const RenderLight& light, const EnvironmentMap& environment,
                                                const CameraFrame& camera, ReferenceModel model,
                                                uint32_t max_interfaces) {
  if (camera.width == 0 || camera.height == 0)
    fail("refraction reference: the camera has {}x{} pixels", camera.width, camera.height);
  RefractionReference out;
  out.build_ms = scene.build_ms();
  const uint32_t width = camera.width, height = camera.height;
  const size_t pixels = size_t(width) * height;
  out.ends.resize(pixels);
  out.paths.resize(pixels);
  const Tracer tracer(scene, materials, light, environment, max_interfaces);

  // One row per block: neighbouring rays share BVH nodes. Every pixel is computed by one call, so nothing
  // depends on the number of threads.
  Clock::time_point start = Clock::now();
  parallel_blocks(height, 1, [&](size_t y0, size_t y1) {
    for (size_t y = y0; y < y1; ++y)
      for (uint32_t x = 0; x < width; ++x) {
        const size_t i = y * width + x;
        tracer.matched(camera.eye, camera.ray_direction(float(x) + 0.5f, float(y) + 0.5f), out.ends[i],
                       out.paths[i]);
      }
  });
  if (model == ReferenceModel::kFull) {
    // The full image is traced, shadows and shading included (shade_ms stays 0).
    out.image = ImageRgba(width, height, glm::vec4(0.0f, 0.0f, 0.0f, 1.0f));
    parallel_blocks(height, 1, [&](size_t y0, size_t y1) {
      for (size_t y = y0; y < y1; ++y)
        for (uint32_t x = 0; x < width; ++x) {
          const glm::vec3 dir = camera.ray_direction(float(x) + 0.5f, float(y) + 0.5f);
          out.image.pixels[y * width + x] =
              glm::vec4(tracer.full(camera.eye, dir, voxr_media_empty(), 0, 1.0f, std::nullopt), 1.0f);
        }
    });
  }
  out.trace_ms = ms_since(start);

  start = Clock::now();
  out.transmittance = scene.transmittance(light, out.ends);
  out.shadow_ms = ms_since(start);

  if (model == ReferenceModel::kMatched) {
    start = Clock::now();
    out.image =
        shade_paths(out.ends, out.transmittance, out.paths, materials, light, environment, width, height);
    out.shade_ms = ms_since(start);
  }
  return out;
}

}  // namespace voxr
