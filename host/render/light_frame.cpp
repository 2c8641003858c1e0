#include "render/light_frame.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <limits>
#include <optional>
#include <vector>

#include "cl/scan.h"
#include "util/error.h"
#include "voxelize/triangle_splitter.h"

namespace voxr {

namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();

// A point light is taken as parallel (an orthographic frame along the ray to the receivers' centre) when that
// moves no shadow by more than this share of a column (a tenth of the column every bilinear lookup blurs an
// edge over): the rays' angle to the axis (at most the receivers' largest, tan t) times the depth from the
// nearest caster to the farthest receiver. Far lights need it: a frustum's slabs, uniform in 1/depth, lose
// float resolution as depth z / depth range d grows, by about n z / d x 2^-24 slabs (n slabs); a light 1e5
// units above a scene of size 1 lost every shadow. Where the parallel frame is refused (z / d below about
// n / (2 x 0.1)), that error stays under n^2 x 3e-7 slabs: 0.02 at n = 256, 0.3 at 1024.
constexpr float kParallelColumns = 0.1f;

std::array<glm::vec3, 8> corners(const Bounds& b) {
  std::array<glm::vec3, 8> c;
  for (int i = 0; i < 8; ++i)
    c[i] = glm::vec3((i & 1) ? b.hi.x : b.lo.x, (i & 2) ? b.hi.y : b.lo.y, (i & 4) ? b.hi.z : b.lo.z);
  return c;
}

// Rows x, y, z of a right-handed orthonormal frame whose z is `forward` (unit).
glm::mat3 frame_rows(const glm::vec3& forward) {
  const glm::vec3 helper = std::abs(forward.y) < 0.9f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0);
  const glm::vec3 x = glm::normalize(glm::cross(helper, forward));
  const glm::vec3 y = glm::cross(forward, x);
  return glm::transpose(glm::mat3(x, y, forward));  // rows
}

void check_resolution(uint32_t resolution) {
  if (resolution < 3 || resolution > 4096) fail("--shadow-res {} is out of range (3..4096)", resolution);
}

}  // namespace

glm::vec3 LightFrame::to_grid(const glm::vec3& p) const {
  const float* m = params.to_light;
  const glm::vec3 q(m[0] * p.x + m[1] * p.y + m[2] * p.z + m[3], m[4] * p.x + m[5] * p.y + m[6] * p.z + m[7],
                    m[8] * p.x + m[9] * p.y + m[10] * p.z + m[11]);
  if (!projective()) return q;
  return glm::vec3((q.x / q.z - params.u0) * params.inv_du, (q.y / q.z - params.v0) * params.inv_dv,
                   (params.inv_near - 1.0f / q.z) * params.depth_scale);
}

std::string LightFrame::describe() const {
  const glm::uvec3 d(params.dims[0], params.dims[1], params.dims[2]);
  if (!projective())
    return fmt::format("orthographic {} x {} x {}, voxel {:.4g}{}", d.x, d.y, d.z, params.voxel_size,
                       parallel_point ? " (point light far enough for parallel rays)" : "");
  const float u1 = params.u0 + float(d.x) / params.inv_du, v1 = params.v0 + float(d.y) / params.inv_dv;
  const float ax = glm::degrees(std::atan(u1) - std::atan(params.u0));
  const float ay = glm::degrees(std::atan(v1) - std::atan(params.v0));
  return fmt::format("frustum {} x {} x {}, depth {:.4g}..{:.4g}, {:.3g} x {:.3g} degrees", d.x, d.y, d.z,
                     near_depth, far_depth, ax, ay);
}

Bounds visible_bounds(const Bounds& scene, const CameraFrame& camera) {
  // The view frustum's corners at the near and far planes.
  Bounds view;
  const float tx = camera.tan_half_fov_y * camera.aspect(), ty = camera.tan_half_fov_y;
  for (float depth : {camera.near_plane, camera.far_plane})
    for (int sx = -1; sx <= 1; sx += 2)
      for (int sy = -1; sy <= 1; sy += 2)
        view.extend(camera.eye +
                    depth * (camera.forward + float(sx) * tx * camera.right + float(sy) * ty * camera.up));
  Bounds out;
  out.lo = glm::max(scene.lo, view.lo);
  out.hi = glm::min(scene.hi, view.hi);
  return out.empty() ? scene : out;
}

namespace {

// Clips triangle `tri` (view-space points) to z >= z_min (Sutherland-Hodgman against one plane): at most 4
// corners, written to `out`; returns how many.
int clip_near(const std::array<glm::vec3, 3>& tri, float z_min, std::array<glm::vec3, 4>& out) {
  int n = 0;
  for (int e = 0; e < 3; ++e) {
    const glm::vec3 a = tri[e], b = tri[(e + 1) % 3];
    const bool ina = a.z >= z_min, inb = b.z >= z_min;
    if (ina) out[n++] = a;
    if (ina != inb) out[n++] = a + (b - a) * ((z_min - a.z) / (b.z - a.z));
  }
  return n;
}

// Light space: (x, y, depth) with x, y the column coordinates (orthographic: world units across the light;
// frustum: x/z and y/z in the light's view) and depth along the light.
struct LightSpace {
  bool projective = false;
  glm::mat3 rows{1.0f};  // the frame's x, y, z axes as rows
  glm::vec3 light{0.0f};
  glm::vec3 operator()(const glm::vec3& p) const {
    if (!projective) return rows * p;
    const glm::vec3 q = rows * (p - light);
    return glm::vec3(q.x / q.z, q.y / q.z, q.z);
  }
  float view_depth(const glm::vec3& p) const { return projective ? (rows * (p - light)).z : (rows * p).z; }
};

struct Footprint {
  glm::vec2 lo{kInf}, hi{-kInf};
  bool empty() const { return lo.x > hi.x || lo.y > hi.y; }
  void extend(glm::vec2 p) {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  bool overlaps(const Footprint& o) const {
    return lo.x <= o.hi.x && o.lo.x <= hi.x && lo.y <= o.hi.y && o.lo.y <= hi.y;
  }
};

// Whether triangle (a, b, c) can shadow a point of `corners`' box: some corner lies beyond its plane, on the
// side away from the light, by more than `eps` (a floor under everything shadows nothing that is visible).
bool casts_on(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c,
              const std::array<glm::vec3, 8>& corners, const RenderLight& light, float eps) {
  const glm::vec3 n = glm::cross(b - a, c - a);
  const float len = glm::length(n);
  if (!(len > 0.0f)) return false;
  const glm::vec3 u = n / len;
  const float light_side =
      light.directional ? -glm::dot(u, glm::vec3(light.direction[0], light.direction[1], light.direction[2]))
                        : glm::dot(u, glm::vec3(light.position[0], light.position[1], light.position[2]) - a);
  for (const glm::vec3& k : corners) {
    const float d = glm::dot(u, k - a);
    if ((light_side >= 0.0f && d < -eps) || (light_side <= 0.0f && d > eps)) return true;
  }
  return false;
}

}  // namespace

namespace {

// What fit_light_frame knows before it looks at a triangle: the light space, the receivers' box, columns and
// depth range, and the casters' tolerance and near cut.
struct FitSetup {
  LightSpace space;
  std::array<glm::vec3, 8> rc;
  float eps = 0.0f;
  Footprint receiving;
  float receivers_near = kInf, receivers_far = -kInf;
  float depth_floor = -kInf;
  // A point light taken as parallel: the tangent of the largest angle between its rays to the receivers'
  // box and the frame's axis (0 otherwise).
  float parallel_tan = 0.0f;
};

// Whether a point light taken as parallel (s.parallel_tan > 0) moves a shadow by more than kParallelColumns
// of a column across the footprint (the columns `n` asks for, before cubic voxels widen them to reach the
// depth), casters reaching to depth `near`: then the frame must be a frustum after all.
bool parallel_too_coarse(const FitSetup& s, const Footprint& fp, float near, uint32_t n) {
  if (s.parallel_tan == 0.0f) return false;
  const float from = near < s.receivers_far ? near : s.receivers_near;
  const glm::vec2 extent = glm::max(fp.hi - fp.lo, glm::vec2(1e-6f));
  const float column = std::max(extent.x, extent.y) / float(n - 2);
  return !(s.parallel_tan * (s.receivers_far - from) <= kParallelColumns * column);
}

// `allow_parallel`: a point light far enough from the receivers (their own depth range, kParallelColumns)
// gets an orthographic frame; the caller checks the casters with parallel_too_coarse and asks again without.
FitSetup setup_fit(const RenderLight& light, const Bounds& receivers, uint32_t resolution,
                   bool allow_parallel) {
  check_resolution(resolution);
  if (receivers.empty()) fail("nothing to shadow: the scene's visible bounds are empty");
  FitSetup s;
  s.rc = corners(receivers);
  const glm::vec3 size = receivers.size();
  s.eps = 1e-4f * std::max({size.x, size.y, size.z, 1e-6f});
  LightSpace& space = s.space;
  space.projective = !light.directional;
  if (light.directional) {
    space.rows =
        frame_rows(glm::normalize(glm::vec3(light.direction[0], light.direction[1], light.direction[2])));
  } else {
    space.light = glm::vec3(light.position[0], light.position[1], light.position[2]);
    const glm::vec3 L = space.light;
    if (glm::all(glm::greaterThan(L, receivers.lo)) && glm::all(glm::lessThan(L, receivers.hi)))
      throw PlacementError("light.position", L,
                           "lies among the receivers: a transparent shadow map's frustum cannot see all "
                           "around it; move it or use a directional light");
    space.rows = frame_rows(glm::normalize(0.5f * (receivers.lo + receivers.hi) - L));
  }
  // The receivers' columns and depth range.
  for (const glm::vec3& c : s.rc) {
    if (space.projective && !(space.view_depth(c) > 0.0f))
      throw PlacementError("light.position", space.light,
                           "is beside or among the receivers: a frustum grid cannot hold them; move the "
                           "light or use a directional light");
    const glm::vec3 q = space(c);
    s.receiving.extend(glm::vec2(q));
    s.receivers_near = std::min(s.receivers_near, q.z);
    s.receivers_far = std::max(s.receivers_far, q.z);
  }
  if (space.projective && allow_parallel) {
    // The frustum's columns at the nearest receiver, in world units, against the shift of a parallel frame
    // over the receivers' own depth range.
    float tan = 0.0f;
    for (const glm::vec3& c : s.rc) {
      const glm::vec3 q = space(c);
      tan = std::max({tan, std::abs(q.x), std::abs(q.y)});
    }
    const glm::vec2 extent = s.receiving.hi - s.receiving.lo;
    const float column = std::max(extent.x, extent.y) * s.receivers_near / float(resolution - 2);
    if (tan * (s.receivers_far - s.receivers_near) <= kParallelColumns * column) {
      space.projective = false;
      s.parallel_tan = std::max(tan, std::numeric_limits<float>::min());
      s.receiving = Footprint{};
      s.receivers_near = kInf;
      s.receivers_far = -kInf;
      for (const glm::vec3& c : s.rc) {
        const glm::vec3 q = space(c);
        s.receiving.extend(glm::vec2(q));
        s.receivers_near = std::min(s.receivers_near, q.z);
        s.receivers_far = std::max(s.receivers_far, q.z);
      }
    }
  }
  // Frustum slabs are uniform in 1/depth: a near plane close to the light would spend them all there. Casters
  // nearer the light than a tenth of the nearest receiver's depth are cut there (their shadow then starts at
  // the cut).
  if (space.projective) s.depth_floor = std::max(1e-3f * s.receivers_far, 0.1f * s.receivers_near);
  return s;
}

// The footprint: the receivers' columns cut down to the casters' (when they overlap at all).
Footprint cut_footprint(const Footprint& receiving, const Footprint& casting) {
  Footprint fp = receiving;
  if (!casting.empty() && casting.overlaps(receiving)) {
    fp.lo = glm::max(receiving.lo, casting.lo);
    fp.hi = glm::min(receiving.hi, casting.hi);
  }
  return fp;
}

// The grid from the footprint and the nearest caster's depth in it (kInf: none).
LightFrame finish_fit(const FitSetup& s, const Footprint& fp, float near, uint32_t n,
                      const glm::dvec3& anchor) {
  LightFrame f;
  const LightSpace& space = s.space;
  // Only casters need slabs: a receiver nearer the light than all of them is lit (depth < 0 in the grid).
  if (!(near < s.receivers_far)) near = s.receivers_near;
  const glm::vec2 extent = glm::max(fp.hi - fp.lo, glm::vec2(1e-6f));
  // One column of margin on every side (bilinear lookups at the edge). Orthographic grids also need their
  // (at most 4 n) cubic voxels to reach from the nearest caster to the farthest receiver.
  float h = std::max(extent.x, extent.y) / float(n - 2);
  if (!space.projective) h = std::max(h, (s.receivers_far - near) / float(4 * n - 1));
  const glm::uvec2 columns(uint32_t(std::ceil(extent.x / h)) + 2, uint32_t(std::ceil(extent.y / h)) + 2);
  if (!space.projective) {
    // Cubic voxels; half a voxel of margin in depth.
    const uint32_t slabs =
        std::min(4 * n, std::max(1u, uint32_t(std::ceil((s.receivers_far - near) / h + 1.0f))));
    const glm::vec3 lo_light(fp.lo.x - h, fp.lo.y - h, near - 0.5f * h);
    f.grid.axes = glm::transpose(space.rows);  // columns: x, y, z axes in world space
    f.grid.origin = f.grid.axes * lo_light;
    f.grid.anchor = anchor;
    f.grid.voxel_size = h;
    f.grid.dims = glm::uvec3(columns, slabs);
    const auto m = f.grid.world_to_grid();
    std::copy(m.begin(), m.end(), f.params.to_light);
    f.params.projective = 0;
    f.params.voxel_size = h;
    f.parallel_point = s.parallel_tan > 0.0f;
  } else {
    const float z_near = std::max(s.depth_floor, near * 0.999f), z_far = s.receivers_far * 1.001f;
    f.grid = GridSpec{};
    f.grid.dims = glm::uvec3(columns, n);
    f.grid.anchor = glm::dvec3(0.0);
    f.light_position = space.light;
    f.view = space.rows;
    f.near_depth = z_near;
    f.far_depth = z_far;
    const glm::mat3 axes = glm::transpose(space.rows);  // columns: the view's x, y, z axes
    for (int r = 0; r < 3; ++r) {
      f.params.to_light[4 * r + 0] = axes[r].x;
      f.params.to_light[4 * r + 1] = axes[r].y;
      f.params.to_light[4 * r + 2] = axes[r].z;
      f.params.to_light[4 * r + 3] = -glm::dot(axes[r], space.light);
    }
    f.params.projective = 1;
    f.params.u0 = fp.lo.x - h;
    f.params.v0 = fp.lo.y - h;
    f.params.inv_du = 1.0f / h;
    f.params.inv_dv = 1.0f / h;
    f.params.inv_near = 1.0f / z_near;
    f.params.depth_scale = float(n) / (1.0f / z_near - 1.0f / z_far);
  }
  f.params.dims[0] = f.grid.dims.x;
  f.params.dims[1] = f.grid.dims.y;
  f.params.dims[2] = f.grid.dims.z;
  return f;
}

// fit_light_frame with or without taking a point light as parallel: nothing when the casters make a parallel
// frame too coarse (parallel_too_coarse).
std::optional<LightFrame> fit_attempt(const RenderLight& light, const Bounds& receivers,
                                      const TriangleSoup& casters, uint32_t resolution, bool allow_parallel) {
  const FitSetup s = setup_fit(light, receivers, resolution, allow_parallel);
  const LightSpace& space = s.space;
  // The columns of the triangles that can shadow a receiver, and their nearest depth.
  Footprint casting;
  // Per casting triangle: its light-space box and nearest depth (vertices in front of the light only).
  struct Caster {
    Footprint box;
    float near;
  };
  std::vector<Caster> casting_triangles;
  for (const glm::uvec4& t : casters.triangles) {
    const glm::vec3 a(casters.positions[t.x]), b(casters.positions[t.y]), c(casters.positions[t.z]);
    if (!casts_on(a, b, c, s.rc, light, s.eps)) continue;
    Caster k{{}, kInf};
    // A triangle reaching behind the light's near cut (projective) counts by its part in front of it.
    std::array<glm::vec3, 4> corners_in_front;
    int n_front = 0;
    if (!space.projective) {
      corners_in_front = {a, b, c, c};
      n_front = 3;
    } else {
      const std::array<glm::vec3, 3> view{space.rows * (a - space.light), space.rows * (b - space.light),
                                          space.rows * (c - space.light)};
      n_front = clip_near(view, s.depth_floor, corners_in_front);
      for (int i = 0; i < n_front; ++i)  // back to world, so space() maps them like any point
        corners_in_front[i] = glm::transpose(space.rows) * corners_in_front[i] + space.light;
    }
    for (int i = 0; i < n_front; ++i) {
      const glm::vec3 q = space(corners_in_front[i]);
      k.box.extend(glm::vec2(q));
      k.near = std::min(k.near, q.z);
    }
    if (k.box.empty()) continue;
    casting.extend(k.box.lo);
    casting.extend(k.box.hi);
    casting_triangles.push_back(k);
  }
  const Footprint fp = cut_footprint(s.receiving, casting);
  float near = kInf;
  for (const Caster& k : casting_triangles)
    if (k.near < near && k.box.overlaps(fp)) near = k.near;
  if (parallel_too_coarse(s, fp, near, resolution)) return std::nullopt;
  return finish_fit(s, fp, near, resolution, casters.anchor);
}

}  // namespace

LightFrame fit_light_frame(const RenderLight& light, const Bounds& receivers, const TriangleSoup& casters,
                           uint32_t resolution) {
  const std::optional<LightFrame> f = fit_attempt(light, receivers, casters, resolution, true);
  return f ? *f : *fit_attempt(light, receivers, casters, resolution, false);  // a frustum always fits
}

TriangleSoup project_to_light_grid(const TriangleSoup& soup, const LightFrame& frame) {
  VOXR_CHECK(frame.projective());
  TriangleSoup out;
  out.anchor = glm::dvec3(0.0);
  const glm::vec3 dims(frame.grid.dims);
  const float z_min = 0.5f * frame.near_depth;
  const ShadowFrame& p = frame.params;
  auto project = [&](const glm::vec3& q) {
    return glm::vec3((q.x / q.z - p.u0) * p.inv_du, (q.y / q.z - p.v0) * p.inv_dv,
                     (p.inv_near - 1.0f / q.z) * p.depth_scale);
  };
  // Every vertex in the light's view and, in front of the near cut, in grid units: once.
  std::vector<glm::vec3> view(soup.positions.size()), grid(soup.positions.size());
  for (size_t v = 0; v < view.size(); ++v) {
    view[v] = frame.view * (glm::vec3(soup.positions[v]) - frame.light_position);
    if (view[v].z >= z_min) grid[v] = project(view[v]);
  }
  out.positions.reserve(soup.positions.size());
  out.triangles.reserve(soup.triangles.size());
  std::vector<uint32_t> mapped(view.size(), ~0u);  // output index of an unclipped vertex
  std::array<glm::vec3, 4> clipped, g;
  for (size_t t = 0; t < soup.triangles.size(); ++t) {
    const glm::uvec4 tri = soup.triangles[t];
    const std::array<glm::vec3, 3> q{view[tri.x], view[tri.y], view[tri.z]};
    const int in_front = int(q[0].z >= z_min) + int(q[1].z >= z_min) + int(q[2].z >= z_min);
    if (in_front == 0) continue;
    const bool whole = in_front == 3;
    int n = 3;
    if (whole) {
      for (int c = 0; c < 3; ++c) g[c] = grid[tri[c]];
    } else {
      n = clip_near(q, z_min, clipped);
      for (int c = 0; c < n; ++c) g[c] = project(clipped[c]);
    }
    // Cull when every corner is beyond the same side of the grid.
    bool outside = false;
    for (int a = 0; a < 3 && !outside; ++a) {
      bool below = true, above = true;
      for (int c = 0; c < n; ++c) {
        below = below && g[c][a] < 0.0f;
        above = above && g[c][a] > dims[a];
      }
      outside = below || above;
    }
    if (outside) continue;
    if (whole) {
      glm::uvec4 out_tri(0, 0, 0, tri.w);
      for (int c = 0; c < 3; ++c) {
        uint32_t& m = mapped[tri[c]];
        if (m == ~0u) {
          m = uint32_t(out.positions.size());
          out.positions.emplace_back(g[c], 1.0f);
        }
        out_tri[c] = m;
      }
      out.triangles.push_back(out_tri);
    } else {
      const uint32_t base = uint32_t(out.positions.size());
      for (int c = 0; c < n; ++c) out.positions.emplace_back(g[c], 1.0f);
      for (int c = 1; c + 1 < n; ++c)
        out.triangles.emplace_back(base, base + uint32_t(c), base + uint32_t(c + 1), tri.w);
    }
  }
  return out;
}

bool LightFitKey::operator==(const LightFitKey& o) const {
  const auto same3 = [](const float* a, const float* b) { return std::memcmp(a, b, 3 * sizeof(float)) == 0; };
  return light.directional == o.light.directional && same3(light.position, o.light.position) &&
         same3(light.direction, o.light.direction) && receivers.lo == o.receivers.lo &&
         receivers.hi == o.receivers.hi && resolution == o.resolution;
}

namespace {

// kernels/render/shadow/light_project.cl's work-group size and reduction slots (passed as defines: one
// source).
constexpr size_t kLightGroup = 256;
enum LightSlot : uint32_t { kCast = 0, kNear = 4, kBoundsSlot = 5, kSplit = 11, kOverflow = 12, kSlots = 13 };
constexpr int kSplitDepth = 16;

Defines light_defines() {
  return {{"WG_SIZE", std::to_string(kLightGroup)},
          {"LIGHT_SPLIT_EXTENT", fmt::format("{:.1f}f", kSplitExtentVoxels)},
          {"LIGHT_SPLIT_DEPTH", std::to_string(kSplitDepth)},
          {"LIGHT_CAST", std::to_string(kCast)},
          {"LIGHT_NEAR", std::to_string(kNear)},
          {"LIGHT_BOUNDS", std::to_string(kBoundsSlot)},
          {"LIGHT_SPLIT", std::to_string(kSplit)},
          {"LIGHT_OVERFLOW", std::to_string(kOverflow)},
          {"LIGHT_SLOTS", std::to_string(kSlots)}};
}

// A float[4] field of a voxr_layout.h struct: xyz and w.
void set4(float (&out)[4], const glm::vec3& v, float w = 0.0f) {
  out[0] = v.x;
  out[1] = v.y;
  out[2] = v.z;
  out[3] = w;
}

float key_value(uint32_t k) {
  const uint32_t u = (k & 0x80000000u) ? (k & 0x7fffffffu) : ~k;
  float f;
  std::memcpy(&f, &u, 4);
  return f;
}

}  // namespace

DeviceLightFrame::DeviceLightFrame(ClRuntime& cl) : cl_(cl) {}

std::vector<ProgramSpec> DeviceLightFrame::programs() const {
  std::vector<ProgramSpec> specs = scan_programs();
  specs.push_back({"light_project.cl", light_defines()});
  return specs;
}

const LightFrame& DeviceLightFrame::fit(const RenderLight& light, const Bounds& receivers,
                                        const DeviceMesh& casters, uint32_t resolution) {
  if (!fit_attempt(light, receivers, casters, resolution, true))
    fit_attempt(light, receivers, casters, resolution, false);  // a frustum always fits
  return frame_;
}

bool DeviceLightFrame::fit_attempt(const RenderLight& light, const Bounds& receivers,
                                   const DeviceMesh& casters, uint32_t resolution, bool allow_parallel) {
  const FitSetup s = setup_fit(light, receivers, resolution, allow_parallel);
  const Defines defines = light_defines();
  cl::Buffer& reduce = reduce_.ensure(cl_, kSlots * 4, "light fit reductions");
  cl::Kernel init = cl_.kernel("light_project.cl", "light_reduce_init", defines);
  cl_.launch("light_fit", init, 1, 1, reduce);
  LightFitParams args{};
  set4(args.receivers_lo, receivers.lo);
  set4(args.receivers_hi, receivers.hi);
  const glm::mat3 axes = glm::transpose(s.space.rows);  // columns: the rows of space.rows
  set4(args.row0, axes[0]);
  set4(args.row1, axes[1]);
  set4(args.row2, axes[2]);
  set4(args.light, light.directional ? glm::vec3(light.direction[0], light.direction[1], light.direction[2])
                                     : s.space.light);
  args.projective = s.space.projective ? 1 : 0;
  args.point = light.directional ? 0 : 1;
  args.eps = s.eps;
  args.depth_floor = s.depth_floor;
  const cl_uint n = casters.triangle_count();
  cl::Kernel casting = cl_.kernel("light_project.cl", "light_fit_casters", defines);
  cl::Buffer& boxes = boxes_.ensure(cl_, uint64_t(n) * 16, "light fit caster boxes");
  cl::Buffer& nears = nears_.ensure(cl_, uint64_t(n) * 4, "light fit caster depths");
  cl_.launch("light_fit", casting, n, kLightGroup, args, casters.positions(), casters.triangles(), n, boxes,
             nears, reduce);
  const cl_float4 receiving = {{s.receiving.lo.x, s.receiving.lo.y, s.receiving.hi.x, s.receiving.hi.y}};
  cl::Kernel nearest = cl_.kernel("light_project.cl", "light_fit_near", defines);
  cl_.launch("light_fit", nearest, n, kLightGroup, receiving, boxes, nears, n, reduce);
  std::array<uint32_t, kSlots> r{};
  cl_.download(reduce, r.data(), 5 * 4, "readback light fit");
  Footprint casting_box;
  casting_box.lo = glm::vec2(key_value(r[kCast + 0]), key_value(r[kCast + 1]));
  casting_box.hi = glm::vec2(key_value(r[kCast + 2]), key_value(r[kCast + 3]));
  const Footprint fp = cut_footprint(s.receiving, casting_box);
  if (parallel_too_coarse(s, fp, key_value(r[kNear]), resolution)) return false;
  frame_ = finish_fit(s, fp, key_value(r[kNear]), resolution, casters.anchor());
  return true;
}

const DeviceMesh& DeviceLightFrame::light_mesh(const DeviceMesh& casters) {
  const LightFrame& f = frame_;
  const Defines defines = light_defines();
  cl::Buffer& reduce = reduce_.ensure(cl_, kSlots * 4, "light fit reductions");
  cl::Kernel init = cl_.kernel("light_project.cl", "light_reduce_init", defines);
  cl_.launch("light_mesh", init, 1, 1, reduce);
  LightPiecesParams args{};
  const std::array<float, 12> m = f.grid.world_to_grid();
  std::copy(m.begin() + 0, m.begin() + 4, args.m0);
  std::copy(m.begin() + 4, m.begin() + 8, args.m1);
  std::copy(m.begin() + 8, m.begin() + 12, args.m2);
  const glm::mat3 view = glm::transpose(f.view);  // columns: the view's rows
  set4(args.view0, view[0]);
  set4(args.view1, view[1]);
  set4(args.view2, view[2]);
  set4(args.light, f.light_position);
  set4(args.dims, glm::vec3(f.grid.dims));
  args.z_min = 0.5f * f.near_depth;
  args.projective = f.projective() ? 1 : 0;
  const cl_uint n = casters.triangle_count();
  cl::Buffer& counts = counts_.ensure(cl_, uint64_t(n) * 4, "light mesh piece counts");
  cl::Buffer& offsets = offsets_.ensure(cl_, uint64_t(n) * 8, "light mesh piece offsets");
  cl::Kernel pieces = cl_.kernel("light_project.cl", "light_pieces", defines);
  // Point light: every vertex projected once (the scene mesh's positions buffer holds exactly its vertices).
  const uint64_t vertices = f.projective() ? casters.positions().getInfo<CL_MEM_SIZE>() / 16 : 0;
  if (vertices > 0xffffffffull) fail("{} vertices are more than 2^32-1", vertices);
  cl::Buffer& projected =
      projected_.ensure(cl_, std::max<uint64_t>(vertices, 1) * 16, "light mesh projected vertices");
  if (vertices > 0) {
    cl::Kernel project = cl_.kernel("light_project.cl", "light_vertices", defines);
    cl_.launch("light_mesh", project, vertices, kLightGroup, args, f.params, casters.positions(),
               cl_uint(vertices), projected);
  }
  // Pass 0 counts; its reductions travel back with the scan's total.
  args.write = 0;
  cl::Buffer& out_positions = positions_.ensure(cl_, 48, "light mesh positions");
  cl::Buffer& out_triangles = triangles_.ensure(cl_, 16, "light mesh triangles");
  cl_.launch("light_mesh", pieces, n, kLightGroup, args, f.params, casters.positions(), casters.triangles(),
             projected, n, counts, offsets, cl_ulong(0), out_positions, out_triangles, reduce);
  reduce_host_.assign(kSlots, 0);
  const std::vector<uint32_t>& r = reduce_host_;
  cl_.download_later(reduce, reduce_host_.data(), kSlots * 4, "readback light mesh counts");
  uint64_t total = 0;
  if (n > 0)
    total = exclusive_scan(cl_, ScanKind::kUintToUlong, counts, offsets, n, "light_mesh");
  else
    cl_.finish("counting the light mesh");
  if (r[kOverflow])
    fail("{} light-grid triangles need more than {} levels of splitting (more than {} voxels long)",
         r[kOverflow], kSplitDepth, kSplitExtentVoxels * float(1u << kSplitDepth));
  const uint64_t split = r[kSplit];
  if (!f.projective() && split == 0) {
    mesh_.reset();
    return casters;
  }
  if (total > 0xffffffffull / 3) fail("the light's grid needs {} triangles, more than 2^32/3", total);
  Bounds bounds = casters.bounds();
  if (f.projective()) {
    bounds.lo = glm::vec3(key_value(r[kBoundsSlot + 0]), key_value(r[kBoundsSlot + 1]),
                          key_value(r[kBoundsSlot + 2]));
    bounds.hi = glm::vec3(key_value(r[kBoundsSlot + 3]), key_value(r[kBoundsSlot + 4]),
                          key_value(r[kBoundsSlot + 5]));
  }
  cl::Buffer& written_positions =
      positions_.ensure(cl_, std::max<uint64_t>(total, 1) * 48, "light mesh positions");
  cl::Buffer& written_triangles =
      triangles_.ensure(cl_, std::max<uint64_t>(total, 1) * 16, "light mesh triangles");
  args.write = 1;
  cl_.launch("light_mesh", pieces, n, kLightGroup, args, f.params, casters.positions(), casters.triangles(),
             projected, n, counts, offsets, cl_ulong(total), written_positions, written_triangles, reduce);
  mesh_ = std::make_unique<DeviceMesh>(written_positions, written_triangles, uint32_t(total), bounds, split);
  return *mesh_;
}

}  // namespace voxr
