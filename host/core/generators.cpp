#include "core/generators.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>

#include "util/error.h"
#include "util/json_reader.h"

namespace voxr {

namespace {

constexpr float kTwoPi = 2.0f * std::numbers::pi_v<float>;
// Upper bound on any tessellation count: keeps a typo from asking for billions of triangles.
constexpr int kMaxTessellation = 4096;
// Upper bound on a foliage block's leaves (2 triangles each), for the same reason.
constexpr int64_t kMaxFoliageLeaves = int64_t(1) << 22;

uint32_t add_vertex(TriangleSoup& soup, glm::vec3 p) {
  soup.positions.push_back(glm::vec4(p, 1.0f));
  return uint32_t(soup.positions.size() - 1);
}

void add_triangle(TriangleSoup& soup, uint32_t a, uint32_t b, uint32_t c, uint32_t material = 0) {
  soup.triangles.push_back(glm::uvec4(a, b, c, material));
}

// Quad a-b-c-d, counter-clockwise seen from the side it faces, as triangles (a,b,c) and (a,c,d).
void add_quad(TriangleSoup& soup, uint32_t a, uint32_t b, uint32_t c, uint32_t d, uint32_t material = 0) {
  add_triangle(soup, a, b, c, material);
  add_triangle(soup, a, c, d, material);
}

// Revolves a profile in the (r, y) half-plane about the Y axis. The first and last points lie on the axis
// (r = 0) and become single pole vertices; the others (r > 0) become rings of `segments` vertices, so the
// surface is closed. The profile must run with the solid on its left (e.g. bottom to top on the outside),
// which makes the winding counter-clockwise seen from outside.
void add_lathe(TriangleSoup& soup, const std::vector<glm::vec2>& profile, int segments, uint32_t material) {
  VOXR_CHECK(profile.size() >= 3);
  VOXR_CHECK(profile.front().x == 0.0f && profile.back().x == 0.0f);
  VOXR_CHECK(segments >= 3);
  const uint32_t n = uint32_t(segments);
  const uint32_t rings = uint32_t(profile.size() - 2);
  const uint32_t bottom = add_vertex(soup, glm::vec3(0.0f, profile.front().y, 0.0f));
  const uint32_t first = uint32_t(soup.positions.size());
  for (uint32_t k = 0; k < rings; ++k) {
    const glm::vec2 p = profile[k + 1];
    VOXR_CHECK(p.x > 0.0f);
    for (uint32_t j = 0; j < n; ++j) {
      const float a = kTwoPi * float(j) / float(n);
      // (r cos a, y, r sin a): d/dprofile x d/da points out of a profile with the solid on its left.
      add_vertex(soup, glm::vec3(p.x * std::cos(a), p.y, p.x * std::sin(a)));
    }
  }
  const uint32_t top = add_vertex(soup, glm::vec3(0.0f, profile.back().y, 0.0f));
  auto ring = [&](uint32_t k, uint32_t j) { return first + k * n + j % n; };
  for (uint32_t j = 0; j < n; ++j) {
    add_triangle(soup, bottom, ring(0, j), ring(0, j + 1), material);
    for (uint32_t k = 0; k + 1 < rings; ++k)
      add_quad(soup, ring(k, j), ring(k + 1, j), ring(k + 1, j + 1), ring(k, j + 1), material);
    add_triangle(soup, ring(rings - 1, j), top, ring(rings - 1, j + 1), material);
  }
}

// Catmull-Rom through `radii` (evenly spaced on t in [0, 1]), each span clamped between its two end
// radii so the curve never dips below the smallest radius given.
float profile_radius(const std::vector<float>& radii, float t) {
  const int spans = int(radii.size()) - 1;
  const float x = std::clamp(t, 0.0f, 1.0f) * float(spans);
  const int i = std::min(int(x), spans - 1);
  const float u = x - float(i);
  auto r = [&](int k) { return radii[std::clamp(k, 0, spans)]; };
  const float p0 = r(i - 1), p1 = r(i), p2 = r(i + 1), p3 = r(i + 2);
  const float v = 0.5f * ((2.0f * p1) + (-p0 + p2) * u + (2.0f * p0 - 5.0f * p1 + 4.0f * p2 - p3) * u * u +
                          (-p0 + 3.0f * p1 - 3.0f * p2 + p3) * u * u * u);
  return std::clamp(v, std::min(p1, p2), std::max(p1, p2));
}

// Uniform float in [0, 1) from the generator's 32-bit output; std::mt19937's sequence is fixed by the
// standard, unlike the standard distributions, so trees are identical across standard libraries.
float uniform(std::mt19937& rng) {
  return float(rng() >> 8) * (1.0f / 16777216.0f);
}

// One leaf centred at `c`: an open quad sheet (2 triangles, 4 vertices of its own) with a random unit normal,
// spun by a random angle about it, `length` in [min_length, min_length + length_span) along the spin
// direction and half that across. Draws 4 numbers from `rng` (normal, spin, length, in that order).
void add_random_leaf(TriangleSoup& soup, std::mt19937& rng, glm::vec3 c, float min_length, float length_span,
                     uint32_t material) {
  // Random unit normal, then a tangent frame spun by a random angle.
  const float z = 2.0f * uniform(rng) - 1.0f, phi = kTwoPi * uniform(rng);
  const float s = std::sqrt(std::max(0.0f, 1.0f - z * z));
  const glm::vec3 n(s * std::cos(phi), z, s * std::sin(phi));
  const glm::vec3 helper = std::abs(n.y) < 0.9f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0);
  const glm::vec3 t0 = glm::normalize(glm::cross(helper, n)), t1 = glm::cross(n, t0);
  const float spin = kTwoPi * uniform(rng);
  const glm::vec3 a = std::cos(spin) * t0 + std::sin(spin) * t1, b = glm::cross(n, a);
  const float length = min_length + length_span * uniform(rng), width = 0.5f * length;
  const glm::vec3 da = 0.5f * length * a, db = 0.5f * width * b;
  // a x b = n, so (-a-b, a-b, a+b, -a+b) is counter-clockwise seen from n.
  const uint32_t v0 = add_vertex(soup, c - da - db), v1 = add_vertex(soup, c + da - db);
  const uint32_t v2 = add_vertex(soup, c + da + db), v3 = add_vertex(soup, c - da + db);
  add_quad(soup, v0, v1, v2, v3, material);
}

}  // namespace

TriangleSoup make_torus(float major, float minor, int rings, int sides) {
  VOXR_CHECK(major > minor && minor > 0.0f);
  VOXR_CHECK(rings >= 3 && sides >= 3);
  TriangleSoup soup;
  soup.positions.reserve(size_t(rings) * sides);
  soup.triangles.reserve(size_t(rings) * sides * 2);
  for (int i = 0; i < rings; ++i) {
    const float u = kTwoPi * float(i) / float(rings);
    for (int j = 0; j < sides; ++j) {
      const float v = kTwoPi * float(j) / float(sides);
      const float r = major + minor * std::cos(v);
      add_vertex(soup, glm::vec3(r * std::cos(u), minor * std::sin(v), r * std::sin(u)));
    }
  }
  auto at = [&](int i, int j) { return uint32_t((i % rings) * sides + j % sides); };
  // Quad (i,j) (i,j+1) (i+1,j+1) (i+1,j): d/dv x d/du points away from the tube's centre line.
  for (int i = 0; i < rings; ++i)
    for (int j = 0; j < sides; ++j) add_quad(soup, at(i, j), at(i, j + 1), at(i + 1, j + 1), at(i + 1, j));
  return soup;
}

TriangleSoup make_uv_sphere(float radius, int stacks, int slices) {
  VOXR_CHECK(radius > 0.0f);
  VOXR_CHECK(stacks >= 2 && slices >= 3);
  std::vector<glm::vec2> profile;
  for (int k = 0; k <= stacks; ++k) {
    const float phi = std::numbers::pi_v<float> * float(k) / float(stacks);
    profile.push_back(k == 0 || k == stacks ? glm::vec2(0.0f, -radius * std::cos(phi))
                                            : radius * glm::vec2(std::sin(phi), -std::cos(phi)));
  }
  TriangleSoup soup;
  add_lathe(soup, profile, slices, 0);
  return soup;
}

TriangleSoup make_box(glm::vec3 lo, glm::vec3 hi) {
  VOXR_CHECK(lo.x < hi.x && lo.y < hi.y && lo.z < hi.z);
  TriangleSoup soup;
  // Corner i has x from bit 0, y from bit 1, z from bit 2.
  for (int i = 0; i < 8; ++i)
    add_vertex(soup, glm::vec3(i & 1 ? hi.x : lo.x, i & 2 ? hi.y : lo.y, i & 4 ? hi.z : lo.z));
  add_quad(soup, 0, 4, 6, 2);  // -x
  add_quad(soup, 1, 3, 7, 5);  // +x
  add_quad(soup, 0, 1, 5, 4);  // -y
  add_quad(soup, 2, 6, 7, 3);  // +y
  add_quad(soup, 0, 2, 3, 1);  // -z
  add_quad(soup, 4, 5, 7, 6);  // +z
  return soup;
}

TriangleSoup make_vase(const VaseParams& p) {
  VOXR_CHECK(p.thickness > 0.0f && p.height > 2.0f * p.thickness);
  VOXR_CHECK(p.profile.size() >= 2);
  for (float r : p.profile) VOXR_CHECK(r > p.thickness);
  VOXR_CHECK(p.segments >= 3 && p.rows >= 1);
  VOXR_CHECK(p.fill >= 0.0f && p.fill <= 1.0f);
  const float h = p.height, t = p.thickness;
  // The inner surface's outline point of row i (shared by the vase and its liquid: one expression).
  const auto inner = [&](int i) {
    const float y = t + (h - t) * float(i) / float(p.rows);
    return glm::vec2(profile_radius(p.profile, y / h) - t, y);
  };
  // Closed outline with the solid on its left: bottom centre, out and up the outside, across the rim,
  // down the inside, to the centre of the inner floor.
  std::vector<glm::vec2> outline{{0.0f, 0.0f}};
  for (int i = 0; i <= p.rows; ++i) {
    const float s = float(i) / float(p.rows);
    outline.push_back({profile_radius(p.profile, s), h * s});
  }
  for (int i = p.rows; i >= 0; --i) outline.push_back(inner(i));
  outline.push_back({0.0f, t});
  TriangleSoup soup;
  add_lathe(soup, outline, p.segments, 0);
  if (p.fill > 0.0f) {
    // The liquid, solid on the left as the vase: inner floor centre, out along the floor, up the inner
    // surface to the fill row, across its top to the axis.
    const int top = std::max(1, int(std::lround(p.fill * float(p.rows))));
    std::vector<glm::vec2> liquid{{0.0f, t}};
    for (int i = 0; i <= top; ++i) liquid.push_back(inner(i));
    liquid.push_back({0.0f, inner(top).y});
    add_lathe(soup, liquid, p.segments, 1);
  }
  return soup;
}

TriangleSoup make_tree(float density, uint32_t seed, float leaf_scale) {
  VOXR_CHECK(density >= 0.0f && leaf_scale > 0.0f);
  TriangleSoup soup;
  // Trunk: a tapered closed cylinder, 12 sides, 4 rows.
  std::vector<glm::vec2> trunk{{0.0f, 0.0f}};
  for (int i = 0; i <= 4; ++i) {
    const float s = float(i) / 4.0f;
    trunk.push_back({0.06f + (0.035f - 0.06f) * s, s});
  }
  trunk.push_back({0.0f, 1.0f});
  add_lathe(soup, trunk, 12, kTreeTrunkMaterial);

  std::mt19937 rng(seed);
  const glm::vec3 crown_center(0.0f, 1.25f, 0.0f), crown_radii(0.55f, 0.45f, 0.55f);
  const long leaves = std::lround(double(kTreeLeavesPerDensity) * density);
  soup.positions.reserve(soup.positions.size() + 4 * size_t(leaves));
  soup.triangles.reserve(soup.triangles.size() + 2 * size_t(leaves));
  for (long l = 0; l < leaves; ++l) {
    glm::vec3 q;
    do {  // uniform in the unit ball
      q = glm::vec3(uniform(rng), uniform(rng), uniform(rng)) * 2.0f - 1.0f;
    } while (glm::dot(q, q) > 1.0f);
    add_random_leaf(soup, rng, crown_center + q * crown_radii, 0.08f * leaf_scale, 0.05f * leaf_scale,
                    kTreeLeafMaterial);
  }
  return soup;
}

TriangleSoup make_foliage(const FoliageParams& p) {
  VOXR_CHECK(p.leaf_size > 0.0f);
  const float reach = kFoliageLeafReach * p.leaf_size;
  VOXR_CHECK(p.size.x > 2.0f * reach && p.size.y > 2.0f * reach && p.size.z > 2.0f * reach);
  TriangleSoup soup;
  soup.positions.reserve(4 * size_t(p.leaves));
  soup.triangles.reserve(2 * size_t(p.leaves));
  std::mt19937 rng(p.seed);
  const glm::vec3 half = 0.5f * p.size - glm::vec3(reach);  // where leaf centres may lie, +-half
  for (uint32_t l = 0; l < p.leaves; ++l) {
    const glm::vec3 u(uniform(rng), uniform(rng), uniform(rng));
    add_random_leaf(soup, rng, (2.0f * u - 1.0f) * half, 0.75f * p.leaf_size, 0.5f * p.leaf_size,
                    kFoliageLeafMaterial);
  }
  return soup;
}

TriangleSoup make_plane(glm::vec2 size, int subdivisions) {
  VOXR_CHECK(size.x > 0.0f && size.y > 0.0f);
  VOXR_CHECK(subdivisions >= 1);
  const int n = subdivisions;
  TriangleSoup soup;
  soup.positions.reserve(size_t(n + 1) * (n + 1));
  soup.triangles.reserve(size_t(n) * n * 2);
  for (int k = 0; k <= n; ++k)    // along z
    for (int i = 0; i <= n; ++i)  // along x
      add_vertex(soup, glm::vec3(size.x * (float(i) / float(n) - 0.5f), 0.0f,
                                 size.y * (float(k) / float(n) - 0.5f)));
  auto at = [&](int i, int k) { return uint32_t(k * (n + 1) + i); };
  // (x,z) -> (x,z+1) -> (x+1,z+1) -> (x+1,z) is counter-clockwise seen from +Y.
  for (int k = 0; k < n; ++k)
    for (int i = 0; i < n; ++i) add_quad(soup, at(i, k), at(i, k + 1), at(i + 1, k + 1), at(i + 1, k));
  return soup;
}

const std::vector<std::string>& generator_names() {
  static const std::vector<std::string> names{"torus", "sphere", "box", "vase", "tree", "plane", "foliage"};
  return names;
}

TriangleSoup make_generated(const std::string& name, const nlohmann::json& params, const std::string& where,
                            const std::string& path) {
  static const nlohmann::json empty = nlohmann::json::object();
  const nlohmann::json& object = params.is_null() ? empty : params;
  auto positive = [](const JsonObjectReader& in, std::string_view key, float fallback) {
    const float v = in.number(key, fallback);
    in.require(v > 0.0f, key, "must be positive");
    return v;
  };
  auto count = [](const JsonObjectReader& in, std::string_view key, int fallback, int lo) {
    return int(in.integer(key, fallback, lo, kMaxTessellation));
  };
  if (name == "torus") {
    const JsonObjectReader in(object, where, path, {"major", "minor", "rings", "sides"});
    const float major = positive(in, "major", 1.0f), minor = positive(in, "minor", 0.4f);
    in.require(minor < major, "minor", "must be smaller than 'major' (a ring torus)");
    return make_torus(major, minor, count(in, "rings", 20, 3), count(in, "sides", 20, 3));
  }
  if (name == "sphere") {
    const JsonObjectReader in(object, where, path, {"radius", "stacks", "slices", "inward"});
    TriangleSoup sphere =
        make_uv_sphere(positive(in, "radius", 1.0f), count(in, "stacks", 16, 2), count(in, "slices", 32, 3));
    // Wound inside out: a cavity in a solid of its material (media_stack.h enters and leaves by winding).
    const nlohmann::json* inward = in.get("inward");
    if (inward && !inward->is_boolean()) in.fail_key("inward", "must be true or false");
    if (inward && inward->get<bool>())
      for (glm::uvec4& t : sphere.triangles) std::swap(t.y, t.z);
    return sphere;
  }
  if (name == "box") {
    const JsonObjectReader in(object, where, path, {"lo", "hi"});
    const glm::vec3 lo = in.vec3("lo", glm::vec3(-0.5f)), hi = in.vec3("hi", glm::vec3(0.5f));
    in.require(lo.x < hi.x && lo.y < hi.y && lo.z < hi.z, "hi", "must be greater than 'lo' on every axis");
    return make_box(lo, hi);
  }
  if (name == "vase") {
    const JsonObjectReader in(object, where, path,
                              {"height", "profile", "thickness", "segments", "rows", "fill"});
    VaseParams p;
    p.height = positive(in, "height", p.height);
    p.profile = in.numbers("profile", p.profile);
    p.thickness = positive(in, "thickness", p.thickness);
    p.segments = count(in, "segments", p.segments, 3);
    p.rows = count(in, "rows", p.rows, 1);
    p.fill = in.number("fill", p.fill);
    in.require(p.fill >= 0.0f && p.fill <= 1.0f, "fill", "must be in [0, 1]");
    in.require(p.profile.size() >= 2, "profile", "needs at least 2 radii");
    for (float r : p.profile)
      in.require(r > p.thickness, "profile",
                 fmt::format("must have every radius above the thickness {}", p.thickness));
    in.require(p.height > 2.0f * p.thickness, "height", "must exceed twice the thickness");
    return make_vase(p);
  }
  if (name == "tree") {
    const JsonObjectReader in(object, where, path, {"density", "seed", "leaf_scale"});
    const float density = in.number("density", 1.0f);
    in.require(density >= 0.0f && density <= 1000.0f, "density", "must be in [0, 1000]");
    const float leaf_scale = in.number("leaf_scale", 1.0f);
    in.require(leaf_scale > 0.0f && leaf_scale <= 10.0f, "leaf_scale", "must be in (0, 10]");
    return make_tree(density, uint32_t(in.integer("seed", 1, 0, 0xffffffffll)), leaf_scale);
  }
  if (name == "plane") {
    const JsonObjectReader in(object, where, path, {"size", "subdivisions"});
    const glm::vec2 size = in.vec2("size", glm::vec2(2.0f));
    in.require(size.x > 0.0f && size.y > 0.0f, "size", "must be positive");
    return make_plane(size, count(in, "subdivisions", 1, 1));
  }
  if (name == "foliage") {
    const JsonObjectReader in(object, where, path, {"size", "leaves", "density", "leaf_size", "seed"});
    FoliageParams p;
    p.size = in.vec3("size", p.size);
    in.require(p.size.x > 0.0f && p.size.y > 0.0f && p.size.z > 0.0f, "size", "must be positive");
    p.leaf_size = positive(in, "leaf_size", p.leaf_size);
    const float smallest = std::min({p.size.x, p.size.y, p.size.z});
    in.require(2.0f * kFoliageLeafReach * p.leaf_size < smallest, "leaf_size",
               fmt::format("must be below {:.4g} so a leaf fits the box's smallest side {} (leaves reach {} "
                           "leaf sizes across)",
                           smallest / (2.0f * kFoliageLeafReach), smallest, 2.0f * kFoliageLeafReach));
    if (in.has("leaves")) in.forbid("density", "cannot be given with 'leaves' (give one of them)");
    if (in.has("density")) {
      const double volume = double(p.size.x) * p.size.y * p.size.z;
      const float density = in.number("density");
      in.require(density >= 0.0f && double(density) * volume <= double(kMaxFoliageLeaves), "density",
                 fmt::format("must be >= 0 and give at most {} leaves in the box's volume {:.4g}",
                             kMaxFoliageLeaves, volume));
      p.leaves = uint32_t(std::llround(double(density) * volume));
    } else {
      p.leaves = uint32_t(in.integer("leaves", p.leaves, 0, kMaxFoliageLeaves));
    }
    p.seed = uint32_t(in.integer("seed", p.seed, 0, 0xffffffffll));
    return make_foliage(p);
  }
  std::string known;
  for (const std::string& n : generator_names()) known += (known.empty() ? "" : ", ") + n;
  fail("{}: unknown generator '{}' (known: {})", where, name, known);
}

}  // namespace voxr
