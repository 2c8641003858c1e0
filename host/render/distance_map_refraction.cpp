#include "render/distance_map_refraction.h"

#include <algorithm>
#include <cmath>

#include "render/placement_error.h"
#include "util/error.h"
#include "voxr_layout.h"

namespace voxr {

namespace {

constexpr size_t kGroup = 64;  // distance_maps.cl's PATH_GROUP
constexpr float kFaces[6][9] = VOXR_CUBE_FACES;
// The cube cameras' near plane, a fraction of the refractor's radius (geometry nearer the reference point
// than this is clipped); the spheres are widened by kMargin so that nothing on them is clipped by the far
// plane.
constexpr float kNearFraction = 1e-3f;
constexpr float kMargin = 1.01f;

float farthest_corner(const Bounds& b, const glm::vec3& from) {
  float r = 0.0f;
  for (int c = 0; c < 8; ++c) {
    const glm::vec3 corner((c & 1) ? b.hi.x : b.lo.x, (c & 2) ? b.hi.y : b.lo.y, (c & 4) ? b.hi.z : b.lo.z);
    r = std::max(r, glm::length(corner - from));
  }
  return r;
}

// Möller-Trumbore in double: 0 when the ray o + t d (t > 0) misses the triangle (a, b, c), else +1 when it
// leaves through it (along the winding normal (b - a) x (c - a)) and -1 when it enters.
int crossing(const glm::dvec3& o, const glm::dvec3& d, const glm::dvec3& a, const glm::dvec3& b,
             const glm::dvec3& c) {
  const glm::dvec3 e1 = b - a, e2 = c - a, p = glm::cross(d, e2);
  const double det = glm::dot(e1, p);  // = -dot(d, e1 x e2)
  if (det == 0.0) return 0;
  const glm::dvec3 s = o - a;
  const double u = glm::dot(s, p) / det;
  if (u < 0.0 || u > 1.0) return 0;
  const glm::dvec3 q = glm::cross(s, e1);
  const double v = glm::dot(d, q) / det;
  if (v < 0.0 || u + v > 1.0) return 0;
  if (!(glm::dot(e2, q) / det > 0.0)) return 0;
  return det < 0.0 ? 1 : -1;
}

// The first material holding `point` by the media stack's winding rule (media_stack.h): a ray from it to
// infinity leaves each solid it is inside once more than it enters, so the signed sum of its crossings is
// the number of nested solids of that material around it; a negative sum (an open or inside-out mesh) falls
// back to parity. corners hold 3 per triangle.
std::optional<uint32_t> material_around(const std::vector<glm::vec3>& corners,
                                        const std::vector<uint32_t>& material_of, uint32_t material_count,
                                        const glm::vec3& point) {
  // Off every axis and every diagonal, so that it meets no edge of an axis-aligned mesh head on.
  const glm::dvec3 dir = glm::normalize(glm::dvec3(0.5384, 0.7213, 0.4357));
  std::vector<int> sum(material_count, 0), count(material_count, 0);
  for (size_t t = 0; t < material_of.size(); ++t) {
    const int c = crossing(glm::dvec3(point), dir, glm::dvec3(corners[3 * t]), glm::dvec3(corners[3 * t + 1]),
                           glm::dvec3(corners[3 * t + 2]));
    sum[material_of[t]] += c;
    count[material_of[t]] += c != 0;
  }
  for (uint32_t m = 0; m < material_count; ++m)
    if (sum[m] > 0 || (sum[m] < 0 && count[m] % 2)) return m;
  return std::nullopt;
}

void collect_dielectrics(const TriangleSoup& soup, const std::vector<Material>& materials,
                         std::vector<glm::vec3>& corners, std::vector<uint32_t>& material_of) {
  corners.clear();
  material_of.clear();
  for (const glm::uvec4& t : soup.triangles) {
    if (t.w >= materials.size() || materials[t.w].kind != MaterialKind::kDielectric) continue;
    for (int v = 0; v < 3; ++v) corners.push_back(glm::vec3(soup.positions[t[v]]));
    material_of.push_back(t.w);
  }
}

}  // namespace

std::optional<uint32_t> dielectric_around(const TriangleSoup& soup, const std::vector<Material>& materials,
                                          const glm::vec3& point) {
  std::vector<glm::vec3> corners;
  std::vector<uint32_t> material_of;
  collect_dielectrics(soup, materials, corners, material_of);
  return material_around(corners, material_of, uint32_t(materials.size()), point);
}

DistanceMapOrigin distance_map_origin(const TriangleSoup& soup, const std::vector<Material>& materials) {
  Bounds dielectric;
  for (const glm::uvec4& t : soup.triangles) {
    if (t.w >= materials.size() || materials[t.w].kind != MaterialKind::kDielectric) continue;
    for (int v = 0; v < 3; ++v) dielectric.extend(glm::vec3(soup.positions[t[v]]));
  }
  const Bounds scene = soup.bounds();
  const Bounds& around = dielectric.empty() ? scene : dielectric;
  DistanceMapOrigin o;
  o.reference = around.empty() ? glm::vec3(0.0f) : 0.5f * (around.lo + around.hi);
  const float radius = around.empty() ? 0.0f : farthest_corner(around, o.reference);
  o.radius = radius > 0.0f ? kMargin * radius : 1.0f;
  const float scene_radius = scene.empty() ? 0.0f : farthest_corner(scene, o.reference);
  o.scene_radius = std::max(o.radius, kMargin * scene_radius);
  return o;
}

CameraFrame cube_face_frame(const glm::vec3& eye, uint32_t face, uint32_t res, float near_plane,
                            float far_plane) {
  VOXR_CHECK(face < 6);
  const float* f = kFaces[face];
  CameraFrame frame;
  frame.eye = eye;
  frame.forward = glm::vec3(f[0], f[1], f[2]);
  frame.right = glm::vec3(f[3], f[4], f[5]);
  frame.up = glm::vec3(f[6], f[7], f[8]);
  frame.tan_half_fov_y = 1.0f;
  frame.width = frame.height = res;
  frame.near_plane = near_plane;
  frame.far_plane = far_plane;
  return frame;
}

DistanceMapRefraction::DistanceMapRefraction(ClRuntime& cl)
    : cl_(cl), rasterizer_(cl, uint64_t(128) << 20, "dm-layers") {}

std::vector<ProgramSpec> DistanceMapRefraction::programs() const {
  std::vector<ProgramSpec> specs = rasterizer_.programs();
  specs.push_back({"distance_maps.cl", {}});
  return specs;
}

void DistanceMapRefraction::set_scene(const TriangleSoup& soup, const std::vector<Material>& materials) {
  origin_ = distance_map_origin(soup, materials);
  collect_dielectrics(soup, materials, dielectric_corners_, dielectric_materials_);
  material_names_.clear();
  for (const Material& m : materials) material_names_.push_back(m.name);
  outside_eye_.reset();
}

void DistanceMapRefraction::resolve_into(const DeviceMesh& mesh, const cl::Buffer& vertex_normals,
                                         const CameraFrame& frame, const cl::Buffer& visibility,
                                         cl::Buffer& out, uint64_t first) {
  rasterizer_.resolve(mesh, vertex_normals, frame, visibility, face_samples_);
  const uint64_t bytes = uint64_t(frame.width) * frame.height * sizeof(SurfaceSample);
  cl::Event event;
  cl_.queue().enqueueCopyBuffer(face_samples_.buffer, out, 0, first * sizeof(SurfaceSample), bytes, nullptr,
                                &event);
  cl_.profiler().record("dm-layers", event);
}

void DistanceMapRefraction::trace(const DeviceMesh& mesh, const cl::Buffer& vertex_normals,
                                  const CameraFrame& camera, const cl::Buffer& materials,
                                  uint32_t material_count, const RefractionOptions& options,
                                  const cl::Buffer& primary_samples, const DielectricPixels& dielectric,
                                  cl::Buffer& end_samples, cl::Buffer& paths) {
  VOXR_CHECK(material_count > 0);
  if (options.layers < 1 || options.layers > kDistanceMapMaxLayers)
    fail("distance-maps: {} layers; 1 to {} are allowed", options.layers, kDistanceMapMaxLayers);
  if (options.layer_res < kDistanceMapMinRes || options.layer_res > kDistanceMapMaxRes)
    fail("distance-maps: layer resolution {}; {} to {} texels are allowed", options.layer_res,
         kDistanceMapMinRes, kDistanceMapMaxRes);
  if (outside_eye_ != camera.eye) {
    if (const std::optional<uint32_t> around = material_around(dielectric_corners_, dielectric_materials_,
                                                               uint32_t(material_names_.size()), camera.eye))
      throw PlacementError(
          "camera.position", camera.eye,
          fmt::format("is inside the dielectric '{}': --refraction distance-maps traces paths "
                      "from outside the glass (its maps hold no surface beyond it); use "
                      "voxel-multi, voxel-exact or reference",
                      material_names_[*around]));
    outside_eye_ = camera.eye;
  }
  const uint32_t res = options.layer_res;
  const uint64_t face_texels = uint64_t(res) * res;
  cl::Buffer& layers =
      layers_.ensure(cl_, options.layers * 6 * face_texels * sizeof(SurfaceSample), "distance map layers");
  cl::Buffer& environment =
      environment_.ensure(cl_, 6 * face_texels * sizeof(SurfaceSample), "distance map environment layer");
  const float near_plane = kNearFraction * origin_.radius;
  for (uint32_t face = 0; face < 6; ++face) {
    // The refractor: dielectrics only, both faces, peeled front to back.
    const CameraFrame inner = cube_face_frame(origin_.reference, face, res, near_plane, origin_.radius);
    RasterTarget target = camera_target(inner);
    target.kind_mask = 1u << VOXR_MATERIAL_DIELECTRIC;
    rasterizer_.bin(mesh, target, materials, material_count, bins_);
    for (uint32_t l = 0; l < options.layers; ++l) {
      GrowingBuffer& current = peel_[l % 2];
      if (l == 0)
        rasterizer_.rasterize_depth(bins_, current);
      else
        rasterizer_.rasterize_depth_peel(bins_, peel_[(l + 1) % 2].buffer, kDistanceMapPeelUlps, current);
      resolve_into(mesh, vertex_normals, inner, current.buffer, layers,
                   (uint64_t(l) * 6 + face) * face_texels);
    }
    // The diffuse environment: everything else, nearest only.
    const CameraFrame outer = cube_face_frame(origin_.reference, face, res, near_plane, origin_.scene_radius);
    RasterTarget env = camera_target(outer);
    env.kind_mask = (1u << VOXR_MATERIAL_OPAQUE) | (1u << VOXR_MATERIAL_SHEET);
    rasterizer_.bin(mesh, env, materials, material_count, bins_);
    rasterizer_.rasterize_depth(bins_, peel_[0]);
    resolve_into(mesh, vertex_normals, outer, peel_[0].buffer, environment, uint64_t(face) * face_texels);
  }

  // The searches' compact copy: one distance per texel, refractor layers then the environment layer.
  const uint64_t layer_texels = options.layers * 6 * face_texels, env_texels = 6 * face_texels;
  cl::Buffer& distances =
      distances_.ensure(cl_, (layer_texels + env_texels) * sizeof(float), "distance map distances");
  cl::Kernel extract = cl_.kernel("distance_maps.cl", "dm_distances");
  cl_.launch("dm-layers", extract, layer_texels, kGroup, layers, cl_uint(layer_texels), cl_ulong(0),
             distances);
  cl_.launch("dm-layers", extract, env_texels, kGroup, environment, cl_uint(env_texels),
             cl_ulong(layer_texels), distances);

  DistanceMapParams p{};
  for (int a = 0; a < 3; ++a) p.reference[a] = origin_.reference[a];
  p.layer_res = res;
  p.layers = options.layers;
  p.max_events = std::clamp<uint32_t>(options.max_events, 1u, VOXR_PATH_MAX_EVENTS);
  p.search_steps = kDistanceMapSearchSteps;
  p.secant_steps = kDistanceMapSecantSteps;
  p.radius = origin_.radius;
  p.scene_radius = origin_.scene_radius;
  p.epsilon = 1e-4f * origin_.radius;
  cl::Kernel kernel = cl_.kernel("distance_maps.cl", "distance_maps");
  VOXR_CHECK_EQ(uint64_t(dielectric.pixel_count()), uint64_t(camera.width) * camera.height);
  cl_.launch("refraction", kernel, dielectric.pixel_count(), kGroup, make_render_camera(camera),
             primary_samples, dielectric, layers, environment, distances, materials, cl_uint(material_count),
             p, mesh.positions(), mesh.triangles(), end_samples, paths);
}

}  // namespace voxr
