#include "reference/reference_scene.h"

#include <embree3/rtcore.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <memory>
#include <mutex>
#include <numeric>
#include <string>
#include <tuple>
#include <type_traits>
#include <vector>

#include "media_stack.h"
#include "reference/parallel_blocks.h"
#include "render/render_scene.h"
#include "render/vertex_normals.h"
#include "util/clock.h"
#include "util/error.h"

namespace voxr {

namespace {

struct DeviceRelease {
  void operator()(RTCDevice device) const { rtcReleaseDevice(device); }
};
struct SceneRelease {
  void operator()(RTCScene scene) const { rtcReleaseScene(scene); }
};
struct GeometryRelease {
  void operator()(RTCGeometry geometry) const { rtcReleaseGeometry(geometry); }
};
using DevicePtr = std::unique_ptr<RTCDeviceTy, DeviceRelease>;
using ScenePtr = std::unique_ptr<RTCSceneTy, SceneRelease>;
using GeometryPtr = std::unique_ptr<RTCGeometryTy, GeometryRelease>;

const char* embree_error_name(RTCError code) {
  switch (code) {
    case RTC_ERROR_NONE:
      return "no error";
    case RTC_ERROR_UNKNOWN:
      return "unknown error";
    case RTC_ERROR_INVALID_ARGUMENT:
      return "invalid argument";
    case RTC_ERROR_INVALID_OPERATION:
      return "invalid operation";
    case RTC_ERROR_OUT_OF_MEMORY:
      return "out of memory";
    case RTC_ERROR_UNSUPPORTED_CPU:
      return "unsupported CPU";
    case RTC_ERROR_CANCELLED:
      return "cancelled";
  }
  return "unrecognized error";
}

// Embree's min_rcp_input: a direction component smaller in magnitude is taken as this (positive) value.
constexpr float kEmbreeMinRcpInput = 1e-18f;

// One hit that the shadow ray's filter saw: distance along the unit direction and the triangle.
struct ShadowHit {
  float t;
  uint32_t triangle;
};

// The context the filter receives: Embree's own first, so the filter can reach the rest.
struct ShadowContext {
  RTCIntersectContext embree;
  uint32_t self;
  std::vector<ShadowHit>* hits;
};
static_assert(std::is_standard_layout_v<ShadowContext>);

// Records every candidate hit (except on `self`) and rejects it, so traversal goes on: Embree calls it for
// every triangle the ray meets within [tnear, tfar], in no particular order.
void record_and_reject(const RTCFilterFunctionNArguments* args) {
  auto* context = reinterpret_cast<ShadowContext*>(args->context);
  for (unsigned i = 0; i < args->N; ++i) {
    if (args->valid[i] == 0) continue;
    const uint32_t triangle = RTCHitN_primID(args->hit, args->N, i);
    if (triangle != context->self) context->hits->push_back({RTCRayN_tfar(args->ray, args->N, i), triangle});
    args->valid[i] = 0;
  }
}

bool shares_vertex(const glm::uvec4& a, const glm::uvec4& b) {
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      if (a[i] == b[j]) return true;
  return false;
}

// One candidate hit of a primary or leaving ray: cast parameter t (along the unit direction), triangle,
// Embree's (u, v).
struct RayHit {
  float t;
  uint32_t triangle;
  float u, v;
};

// The context of ReferenceScene::intersect's casts, Embree's own first so the filter can reach the rest.
struct NearestContext {
  RTCIntersectContext embree;
  const std::vector<glm::uvec4>* triangles;
  std::span<const uint32_t> leaving;  // skipped at any t
  float neighbour_t;                  // their vertex-sharing neighbours are skipped at cast t <= this
  std::vector<RayHit>* window;        // null: accept the rest (nearest); else record and reject every one
};
static_assert(std::is_standard_layout_v<NearestContext>);

void skip_left(const RTCFilterFunctionNArguments* args) {
  const auto* context = reinterpret_cast<const NearestContext*>(args->context);
  for (unsigned i = 0; i < args->N; ++i) {
    if (args->valid[i] == 0) continue;
    const uint32_t triangle = RTCHitN_primID(args->hit, args->N, i);
    const float t = RTCRayN_tfar(args->ray, args->N, i);
    bool skip = false;
    for (uint32_t left : context->leaving) {
      skip = skip || triangle == left ||
             (t <= context->neighbour_t &&
              shares_vertex((*context->triangles)[triangle], (*context->triangles)[left]));
    }
    if (!skip && context->window) {
      context->window->push_back(
          {t, triangle, RTCHitN_u(args->hit, args->N, i), RTCHitN_v(args->hit, args->N, i)});
      skip = true;
    }
    if (skip) args->valid[i] = 0;
  }
}

uint32_t find_root(std::vector<uint32_t>& parent, uint32_t i) {
  while (parent[i] != i) i = parent[i] = parent[parent[i]];
  return i;
}

}  // namespace

struct ReferenceScene::Impl {
  DevicePtr device;
  // The BVH of the scene mirrored in the axes of bit mask i (x 1, y 2, z 4), scenes[0] the scene itself; the
  // others are built on first use (see for_each_cast).
  std::array<ScenePtr, 8> scenes;
  std::array<std::once_flag, 8> built;
  std::vector<glm::vec3> positions;
  std::vector<glm::uvec4> triangles;  // xyz: vertices, w: material
  std::vector<glm::vec3> normals;     // per vertex, vertex_normals()
  std::vector<Material> materials;
  Bounds bounds;
  float size = 1.0f;  // largest side of the bounds (1 for an empty or flat-to-a-point scene)
  double build_ms = 0.0;

  std::mutex error_mutex;
  std::string last_error;  // the message of Embree's last error callback

  void check(const char* what) {
    const RTCError code = rtcGetDeviceError(device.get());
    if (code == RTC_ERROR_NONE) return;
    const std::lock_guard<std::mutex> lock(error_mutex);
    fail("reference scene: Embree failed to {}: {}{}{}", what, embree_error_name(code),
         last_error.empty() ? "" : ": ", last_error);
  }

  glm::vec3 position(uint32_t triangle, int corner) const { return positions[triangles[triangle][corner]]; }
  // Unit normal of the triangle's winding (cross(p1 - p0, p2 - p0)), 0 for a zero-area triangle.
  glm::vec3 face_normal(uint32_t triangle) const {
    const glm::vec3 p0 = position(triangle, 0);
    const glm::vec3 n = glm::cross(position(triangle, 1) - p0, position(triangle, 2) - p0);
    const float len = glm::length(n);
    return len > 0.0f ? n / len : glm::vec3(0.0f);
  }

  bool crosses(std::span<const uint32_t> faces, const glm::vec3& dir) const;
  bool nearest(const glm::vec3& origin, const glm::vec3& d, float t_near, float t_far,
               std::span<const uint32_t> leaving, float neighbour_t, RayHit& out);
  // The SurfaceSample of `hit` at origin + t d (d unit; distance max(t, 0)).
  SurfaceSample sample(const glm::vec3& origin, const glm::vec3& d, const RayHit& hit, float t) const;
  ScenePtr build(unsigned mirror);
  RTCScene scene(unsigned mirror) {
    std::call_once(built[mirror], [&] { scenes[mirror] = build(mirror); });
    return scenes[mirror].get();
  }

  // Embree culls a BVH node whose upper bound equals the ray's origin in an axis the ray's direction is 0 in
  // (its slab test meets 0 * 1e18 there, so the ray leaves the box at t = 0): an axis-aligned ray exactly on
  // a box's top edge would miss the box. In the scene mirrored in that axis such a node's bound is a lower
  // one, which the test keeps; mirroring negates coordinates, which floats do exactly, so the mirrored
  // scene's hits are the same (t, triangle, u, v). cast(scene, origin, dir) is called for the scene and for
  // every mirror in a subset of the axes where dir is 0 (1 call for a generic ray, 4 for an axis-parallel
  // one); the union of their hits is every hit.
  template <typename Cast>
  void for_each_cast(const glm::vec3& origin, const glm::vec3& dir, Cast&& cast) {
    unsigned zero = 0;
    for (int c = 0; c < 3; ++c)
      if (std::abs(dir[c]) < kEmbreeMinRcpInput) zero |= 1u << c;
    for (unsigned mirror = zero;; mirror = (mirror - 1) & zero) {  // every subset of `zero`
      const glm::vec3 sign(mirror & 1 ? -1.0f : 1.0f, mirror & 2 ? -1.0f : 1.0f, mirror & 4 ? -1.0f : 1.0f);
      cast(scene(mirror), origin * sign, dir * sign);
      if (mirror == 0) break;
    }
  }
};

// Whether the ray through one point shared by `faces` (distinct triangles, no two with the same vertex set,
// each sharing a vertex with another) passes through the surface there or only touches it.
bool ReferenceScene::Impl::crosses(std::span<const uint32_t> faces, const glm::vec3& dir) const {
  if (faces.size() < 2) return true;
  const glm::dvec3 d(dir);
  if (faces.size() == 2) {
    const glm::uvec4 &a = triangles[faces[0]], &b = triangles[faces[1]];
    uint32_t shared[3], count = 0, third_a = 0, third_b = 0;
    for (int i = 0; i < 3; ++i) {
      bool in_b = false;
      for (int j = 0; j < 3; ++j) in_b = in_b || a[i] == b[j];
      if (in_b)
        shared[count++] = a[i];
      else
        third_a = a[i];
    }
    if (count == 2) {
      for (int j = 0; j < 3; ++j)
        if (b[j] != shared[0] && b[j] != shared[1]) third_b = b[j];
      // Through the shared edge: a crossing when the two third vertices project to opposite sides of the
      // edge as seen along the ray (the surface continues across), a touch when to the same side (a fold
      // the ray grazes). Independent of the winding; in double.
      const glm::dvec3 e0(positions[shared[0]]), edge = glm::dvec3(positions[shared[1]]) - e0;
      const double side_a = glm::dot(d, glm::cross(edge, glm::dvec3(positions[third_a]) - e0));
      const double side_b = glm::dot(d, glm::cross(edge, glm::dvec3(positions[third_b]) - e0));
      return !(side_a * side_b > 0.0);
    }
  }
  // Through a shared vertex: a crossing when every face meets the ray from the same side (by winding), a
  // touch (a corner grazed) otherwise.
  bool front = false, back = false;
  for (uint32_t f : faces) {
    const double facing = glm::dot(d, glm::dvec3(face_normal(f)));
    front = front || facing < 0.0;
    back = back || facing > 0.0;
  }
  return !(front && back);
}

ScenePtr ReferenceScene::Impl::build(unsigned mirror) {
  const glm::vec3 sign(mirror & 1 ? -1.0f : 1.0f, mirror & 2 ? -1.0f : 1.0f, mirror & 4 ? -1.0f : 1.0f);
  ScenePtr scene(rtcNewScene(device.get()));
  check("create a scene");
  // Robust: the watertight (Pluecker) triangle test, so a ray through an edge hits at least one side.
  // Context filter: the shadow rays' filter rides on the context; primary rays pass none.
  rtcSetSceneFlags(scene.get(), RTC_SCENE_FLAG_ROBUST | RTC_SCENE_FLAG_CONTEXT_FILTER_FUNCTION);
  rtcSetSceneBuildQuality(scene.get(), RTC_BUILD_QUALITY_MEDIUM);
  if (!triangles.empty()) {
    GeometryPtr geometry(rtcNewGeometry(device.get(), RTC_GEOMETRY_TYPE_TRIANGLE));
    check("create the triangle geometry");
    auto* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(
        geometry.get(), RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), positions.size()));
    auto* indices = static_cast<uint32_t*>(rtcSetNewGeometryBuffer(
        geometry.get(), RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(uint32_t), triangles.size()));
    check("allocate the geometry's buffers");
    for (size_t v = 0; v < positions.size(); ++v)
      for (int c = 0; c < 3; ++c) vertices[3 * v + c] = positions[v][c] * sign[c];
    for (size_t i = 0; i < triangles.size(); ++i)
      for (int c = 0; c < 3; ++c) indices[3 * i + c] = triangles[i][c];
    rtcCommitGeometry(geometry.get());
    rtcAttachGeometry(scene.get(), geometry.get());
    check("attach the triangle geometry");
  }
  rtcCommitScene(scene.get());
  check("build the BVH");
  return scene;
}

ReferenceScene::ReferenceScene(const TriangleSoup& soup, const std::vector<Material>& materials)
    : impl_(std::make_unique<Impl>()) {
  Impl& m = *impl_;
  const Clock::time_point start = Clock::now();
  const size_t vertex_count = soup.positions.size();
  for (size_t i = 0; i < soup.triangles.size(); ++i) {
    const glm::uvec4& t = soup.triangles[i];
    if (t.x >= vertex_count || t.y >= vertex_count || t.z >= vertex_count)
      fail("reference scene: triangle {} names vertex {} but there are {}", i, std::max({t.x, t.y, t.z}),
           vertex_count);
    if (t.w >= materials.size())
      fail("reference scene: triangle {} has material {} but there are {} materials", i, t.w,
           materials.size());
  }
  if (soup.triangles.size() > std::numeric_limits<uint32_t>::max() - 1)
    fail("reference scene: {} triangles, more than Embree's 32-bit ids hold", soup.triangles.size());
  m.positions.resize(vertex_count);
  for (size_t v = 0; v < vertex_count; ++v) m.positions[v] = glm::vec3(soup.positions[v]);
  m.triangles.assign(soup.triangles.begin(), soup.triangles.end());
  m.normals = vertex_normals(soup);
  m.materials = materials;
  m.bounds = soup.bounds();
  const glm::vec3 size = m.bounds.size();
  const float largest = std::max({size.x, size.y, size.z});
  m.size = largest > 0.0f && std::isfinite(largest) ? largest : 1.0f;

  m.device.reset(rtcNewDevice(nullptr));
  if (!m.device)
    fail("reference scene: Embree could not create a device: {}",
         embree_error_name(rtcGetDeviceError(nullptr)));
  rtcSetDeviceErrorFunction(
      m.device.get(),
      [](void* user, RTCError, const char* message) {
        auto* impl = static_cast<Impl*>(user);
        const std::lock_guard<std::mutex> lock(impl->error_mutex);
        impl->last_error = message ? message : "";
      },
      &m);
  m.scene(0);  // the scene itself now, its mirrors on first use
  m.build_ms = ms_since(start);
}

ReferenceScene::~ReferenceScene() = default;

double ReferenceScene::build_ms() const {
  return impl_->build_ms;
}
float ReferenceScene::scene_size() const {
  return impl_->size;
}

namespace {

// A ray o + t e, t in [t_near, t_far], with no hit yet.
RTCRayHit embree_ray(const glm::vec3& o, const glm::vec3& e, float t_near, float t_far) {
  RTCRayHit rh{};
  rh.ray.org_x = o.x;
  rh.ray.org_y = o.y;
  rh.ray.org_z = o.z;
  rh.ray.dir_x = e.x;
  rh.ray.dir_y = e.y;
  rh.ray.dir_z = e.z;
  rh.ray.tnear = t_near;
  rh.ray.tfar = t_far;
  rh.ray.mask = 0xffffffffu;
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  return rh;
}

}  // namespace

// The nearest hit of origin + t d (d unit), t in [t_near, t_far] (cast parameters), skipping as `leaving`
// and neighbour_t say (NearestContext), with the coincident-hit rule (ReferenceScene::intersect): false on
// a miss.
bool ReferenceScene::Impl::nearest(const glm::vec3& origin, const glm::vec3& d, float t_near, float t_far,
                                   std::span<const uint32_t> leaving, float neighbour_t, RayHit& out) {
  NearestContext context;
  rtcInitIntersectContext(&context.embree);
  context.triangles = &triangles;
  context.leaving = leaving;
  context.neighbour_t = neighbour_t;
  context.window = nullptr;
  if (!leaving.empty()) context.embree.filter = skip_left;
  // The nearest hit over the casts (the lowest triangle of equally near ones).
  out = {std::numeric_limits<float>::infinity(), VOXR_NO_TRIANGLE, 0.0f, 0.0f};
  for_each_cast(origin, d, [&](RTCScene scene, const glm::vec3& o, const glm::vec3& e) {
    RTCRayHit rh = embree_ray(o, e, t_near, t_far);
    rtcIntersect1(scene, &context.embree, &rh);
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return;
    if (rh.ray.tfar < out.t || (rh.ray.tfar == out.t && rh.hit.primID < out.triangle))
      out = {rh.ray.tfar, rh.hit.primID, rh.hit.u, rh.hit.v};
  });
  if (out.triangle == VOXR_NO_TRIANGLE) return false;
  // An opaque nearest hit wins (of coincident opaque ones the nearer, then the lower id: deterministic, and
  // either ends the ray). Otherwise every hit within the merge distance beyond it: the one that wins is
  // opaque if any is, then one the ray enters (its winding faces the ray: glass to water at a shared face is
  // one interface, not glass to air to water), then the lowest triangle id; t itself (which rounding orders)
  // has no say.
  if (materials[triangles[out.triangle].w].kind == MaterialKind::kOpaque) return true;
  std::vector<RayHit> window;
  context.embree.filter = skip_left;
  context.window = &window;
  const float merge = kMergeDistance * size;
  for_each_cast(origin, d, [&](RTCScene scene, const glm::vec3& o, const glm::vec3& e) {
    RTCRayHit rh = embree_ray(o, e, std::max(t_near, out.t - merge), std::min(t_far, out.t + merge));
    rtcIntersect1(scene, &context.embree, &rh);
  });
  const auto rank = [&](const RayHit& h) {
    return std::tuple(materials[triangles[h.triangle].w].kind == MaterialKind::kOpaque ? 0 : 1,
                      glm::dot(face_normal(h.triangle), d) < 0.0f ? 0 : 1, h.triangle);
  };
  const float t0 = out.t;
  for (const RayHit& h : window)
    if (h.t <= t0 + merge && rank(h) < rank(out)) out = h;
  return true;
}

SurfaceSample ReferenceScene::Impl::sample(const glm::vec3& origin, const glm::vec3& d, const RayHit& hit,
                                           float t_hit) const {
  SurfaceSample s{};
  const glm::uvec4& t = triangles[hit.triangle];
  const glm::vec3 position = origin + t_hit * d;
  glm::vec3 geometric = face_normal(hit.triangle);
  // The crease rule per corner (voxr_layout.h VOXR_CREASE_COS), as the rasterizer's resolve applies it.
  const auto corner = [&](uint32_t vertex) {
    const glm::vec3 n = normals[vertex];
    return glm::dot(n, geometric) >= VOXR_CREASE_COS ? n : geometric;
  };
  const float u = hit.u, v = hit.v;
  glm::vec3 shading = (1.0f - u - v) * corner(t.x) + u * corner(t.y) + v * corner(t.z);
  const float shading_len = glm::length(shading);
  shading = shading_len > 0.0f ? shading / shading_len : glm::vec3(0.0f);
  if (!(glm::dot(shading, geometric) >= VOXR_CREASE_COS)) shading = geometric;
  // Turned towards the ray as the rasterizer's resolve does (raster_resolve.cl): the shading normal with the
  // geometric one's flip, and the geometric normal where it still faces away. Flipping each on its own
  // turned a silhouette's shading normal into the glass, so a "refracted" ray left the surface while the
  // path recorded it inside.
  if (glm::dot(geometric, d) > 0.0f) {
    geometric = -geometric;
    shading = -shading;
  }
  if (glm::dot(shading, d) > 0.0f) shading = geometric;
  for (int c = 0; c < 3; ++c) {
    s.position[c] = position[c];
    s.normal[c] = shading[c];
    s.geometric_normal[c] = geometric[c];
  }
  s.triangle = hit.triangle;
  s.material = t.w;
  s.distance = std::max(t_hit, 0.0f);
  s.barycentric[0] = u;
  s.barycentric[1] = v;
  return s;
}

namespace {

SurfaceSample no_hit() {
  SurfaceSample s{};
  s.triangle = VOXR_NO_TRIANGLE;
  return s;
}

// dir / |dir|, or voxr::Error for a zero or non-finite dir.
glm::vec3 unit_direction(const glm::vec3& dir, float& len) {
  len = glm::length(dir);
  if (!(len > 0.0f) || !std::isfinite(len))
    fail("reference intersect: the ray direction ({}, {}, {}) is zero or not finite", dir.x, dir.y, dir.z);
  return dir / len;
}

}  // namespace

SurfaceSample ReferenceScene::intersect(const glm::vec3& origin, const glm::vec3& dir, float t_near,
                                        float t_far) const {
  float len = 0.0f;
  const glm::vec3 d = unit_direction(dir, len);
  RayHit hit;
  if (!impl_->nearest(origin, d, t_near * len, t_far * len, {}, 0.0f, hit)) return no_hit();
  return impl_->sample(origin, d, hit, hit.t);
}

SurfaceSample ReferenceScene::intersect_leaving(const glm::vec3& origin, const glm::vec3& dir,
                                                std::span<const uint32_t> leaving) const {
  Impl& m = *impl_;
  if (leaving.empty() || leaving.size() > 8)
    fail("reference intersect: a ray leaves {} triangles (1 to 8)", leaving.size());
  for (uint32_t left : leaving)
    if (left >= m.triangles.size())
      fail("reference intersect: the ray leaves triangle {} but there are {}", left, m.triangles.size());
  float len = 0.0f;
  const glm::vec3 d = unit_direction(dir, len);
  // Cast from `back` behind the origin, so a surface through the origin is met at cast t ~ back.
  const float back = kMergeDistance * m.size;
  const glm::vec3 start = origin - back * d;
  RayHit hit;
  if (!m.nearest(start, d, 0.0f, std::numeric_limits<float>::infinity(), leaving, 2.0f * back, hit))
    return no_hit();
  return m.sample(origin, d, hit, hit.t - back);
}

glm::vec3 ReferenceScene::winding_normal(uint32_t triangle) const {
  if (triangle >= impl_->triangles.size())
    fail("reference scene: triangle {} of {}", triangle, impl_->triangles.size());
  return impl_->face_normal(triangle);
}

glm::vec3 ReferenceScene::transmittance(const RenderLight& light, const glm::vec3& point,
                                        uint32_t self) const {
  Impl& m = *impl_;
  const LightAtPoint at = light_at(light, point);
  if (!light.directional && !(at.distance > 0.0f)) return glm::vec3(1.0f);  // the light is at the point
  const glm::vec3 dir = at.to_light;
  // The segment ends at the light; beyond it the ray goes on to infinity only to count dielectric
  // crossings (their sum says how deep inside solids the segment starts).
  const float t_end = at.distance;
  const float epsilon = kStartEpsilon * m.size;
  const float merge = kMergeDistance * m.size;

  std::vector<ShadowHit> hits;
  ShadowContext context;
  rtcInitIntersectContext(&context.embree);
  context.embree.filter = record_and_reject;
  context.self = self;
  context.hits = &hits;
  m.for_each_cast(point, dir, [&](RTCScene scene, const glm::vec3& o, const glm::vec3& e) {
    RTCRayHit rh = embree_ray(o, e, epsilon, std::numeric_limits<float>::infinity());
    rtcIntersect1(scene, &context.embree, &rh);
  });
  if (hits.empty()) return glm::vec3(1.0f);
  std::sort(hits.begin(), hits.end(), [](const ShadowHit& a, const ShadowHit& b) {
    return a.t < b.t || (a.t == b.t && a.triangle < b.triangle);
  });

  // Crossings: hits closer than `merge` along the ray on triangles that share a vertex (transitively) are
  // one place where the ray meets one mesh, at an edge or a vertex; coincident triangles with no common
  // vertex stay apart.
  const uint32_t n = uint32_t(hits.size());
  std::vector<uint32_t> parent(n);
  std::iota(parent.begin(), parent.end(), 0u);
  for (uint32_t j = 1; j < n; ++j)
    for (uint32_t i = j; i-- > 0 && hits[j].t - hits[i].t < merge;)
      if (shares_vertex(m.triangles[hits[i].triangle], m.triangles[hits[j].triangle])) {
        const uint32_t a = find_root(parent, i), b = find_root(parent, j);
        parent[std::max(a, b)] = std::min(a, b);  // a group's root is its first hit
      }
  // The groups in t order: the hits sorted by (root, index).
  std::vector<uint32_t> order(n);
  for (uint32_t i = 0; i < n; ++i) parent[i] = find_root(parent, i);
  std::iota(order.begin(), order.end(), 0u);
  std::stable_sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) { return parent[a] < parent[b]; });

  // Per group: its distinct faces (one per vertex set: a face listed twice, or reported twice, is one
  // surface), whether the ray crosses the surface there or only touches it, and one event per distinct
  // material at the group's first t.
  struct Event {
    float t;
    uint32_t material;
    bool enters;  // the group's first face of the material faces the ray (media_stack.h)
  };
  std::vector<Event> events;
  std::vector<uint32_t> faces, materials_here;
  std::vector<glm::uvec3> face_keys;
  for (uint32_t begin = 0; begin < n;) {
    const uint32_t root = parent[order[begin]];
    uint32_t end = begin;
    faces.clear();
    face_keys.clear();
    materials_here.clear();
    for (; end < n && parent[order[end]] == root; ++end) {
      const uint32_t f = hits[order[end]].triangle;
      glm::uvec3 key(m.triangles[f]);
      std::sort(&key[0], &key[0] + 3);
      if (std::find(face_keys.begin(), face_keys.end(), key) == face_keys.end()) {
        face_keys.push_back(key);
        faces.push_back(f);
      }
      const uint32_t material = m.triangles[f].w;
      if (std::find(materials_here.begin(), materials_here.end(), material) == materials_here.end())
        materials_here.push_back(material);
    }
    begin = end;
    if (!m.crosses(faces, dir)) continue;
    for (uint32_t material : materials_here) {
      uint32_t first = faces.front();
      for (uint32_t f : faces)
        if (m.triangles[f].w == material) {
          first = f;
          break;
        }
      events.push_back({hits[root].t, material, glm::dot(m.face_normal(first), dir) < 0.0f});
    }
  }

  // Per dielectric material met: its crossings over the whole ray (media_stack.h's ledger).
  std::vector<VoxrSolidLedger> solids;
  glm::vec3 result(1.0f);
  bool blocked = false;
  for (const Event& e : events) {
    const Material& material = m.materials[e.material];
    const bool before = e.t < t_end;
    switch (material.kind) {
      case MaterialKind::kOpaque:
        blocked = blocked || before;
        break;
      case MaterialKind::kSheet:
        if (before) result *= material.transmittance;
        break;
      case MaterialKind::kDielectric: {
        auto s = std::find_if(solids.begin(), solids.end(),
                              [&](const VoxrSolidLedger& l) { return l.material == e.material; });
        if (s == solids.end()) s = solids.insert(solids.end(), voxr_ledger_make(e.material));
        voxr_ledger_cross(&*s, e.t, e.enters ? 1 : 0, before ? 1 : 0);
        break;
      }
    }
    if (blocked) return glm::vec3(0.0f);
  }
  for (const VoxrSolidLedger& s : solids) {
    const float length = voxr_ledger_inside_length(&s, t_end);
    const glm::vec3 sigma = m.materials[s.material].absorption;
    for (int c = 0; c < 3; ++c)
      if (length > 0.0f) result[c] *= std::exp(-sigma[c] * length);
  }
  return result;
}

std::vector<glm::vec3> ReferenceScene::transmittance(const RenderLight& light,
                                                     std::span<const SurfaceSample> samples) const {
  std::vector<glm::vec3> out(samples.size(), glm::vec3(1.0f));
  parallel_blocks(samples.size(), 256, [&](size_t begin, size_t end) {
    for (size_t i = begin; i < end; ++i) {
      const SurfaceSample& s = samples[i];
      if (s.triangle == VOXR_NO_TRIANGLE) continue;
      out[i] = transmittance(light, glm::vec3(s.position[0], s.position[1], s.position[2]), s.triangle);
    }
  });
  return out;
}

}  // namespace voxr
