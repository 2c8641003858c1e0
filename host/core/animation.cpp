#include "core/animation.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "core/scene.h"
#include "util/error.h"
#include "util/json_reader.h"
#include "util/text_scan.h"

namespace voxr {

using nlohmann::json;

glm::mat4 KeyPose::matrix() const {
  glm::mat4 m = glm::mat4_cast(rotation);
  m[0] *= scale.x;
  m[1] *= scale.y;
  m[2] *= scale.z;
  m[3] = glm::vec4(translate, 1.0f);
  return m;
}

namespace {

// X, then Y, then Z, as make_transform.
glm::quat euler_quat(glm::vec3 rotate_deg) {
  const glm::vec3 r = glm::radians(rotate_deg);
  return glm::angleAxis(r.z, glm::vec3(0, 0, 1)) * glm::angleAxis(r.y, glm::vec3(0, 1, 0)) *
         glm::angleAxis(r.x, glm::vec3(1, 0, 0));
}

KeyPose key_pose(const TransformKey& k) {
  return {k.scale, euler_quat(k.rotate_deg), k.translate};
}

}  // namespace

KeyPose interpolate_keys(const std::vector<TransformKey>& keys, double t) {
  VOXR_CHECK(!keys.empty());
  if (!(t > keys.front().time)) return key_pose(keys.front());
  if (t >= keys.back().time) return key_pose(keys.back());
  // keys[i].time <= t < keys[i + 1].time
  const size_t i = size_t(std::upper_bound(keys.begin(), keys.end(), t,
                                           [](double v, const TransformKey& k) { return v < k.time; }) -
                          keys.begin()) -
                   1;
  const TransformKey &a = keys[i], &b = keys[i + 1];
  if (t == a.time) return key_pose(a);
  const float s = float((t - a.time) / (b.time - a.time));
  return {glm::mix(a.scale, b.scale, s), glm::slerp(euler_quat(a.rotate_deg), euler_quat(b.rotate_deg), s),
          glm::mix(a.translate, b.translate, s)};
}

glm::dvec3 deform_point(const std::vector<Deform>& deforms, glm::dvec3 p, double base_y, double t) {
  constexpr double kTwoPi = 2.0 * std::numbers::pi;
  for (const Deform& d : deforms) {
    const double h = p.y - base_y;
    switch (d.kind) {
      case DeformKind::kSway:
        p += glm::dvec3(d.axis) *
             (double(d.amplitude) * h * std::sin(kTwoPi * d.frequency_hz * t + double(d.phase_per_unit) * h));
        break;
      case DeformKind::kTwist: {
        const double angle =
            glm::radians(double(d.degrees_per_unit) * h) * std::sin(kTwoPi * d.frequency_hz * t);
        const double c = std::cos(angle), s = std::sin(angle);
        // Counter-clockwise seen from +Y (right-handed, as glm::rotate about +Y).
        p = glm::dvec3(c * p.x + s * p.z, p.y, -s * p.x + c * p.z);
        break;
      }
    }
  }
  return p;
}

namespace {

TransformKey parse_key(const json& value, const std::string& where, const std::string& path) {
  const JsonObjectReader in(value, where, path, {"time", "scale", "rotate_deg", "translate"});
  TransformKey k;
  const json* time = in.get("time");
  if (!time) fail("{}: missing required key '{}'", where, in.path("time"));
  if (!time->is_number())
    in.fail_key("time", fmt::format("must be a number of seconds (got {})", shown(*time)));
  k.time = time->get<double>();
  in.require(std::isfinite(k.time) && k.time >= 0.0, "time", "must be a finite number of seconds >= 0");
  k.scale = in.scale("scale", glm::vec3(1.0f));
  k.rotate_deg = in.vec3("rotate_deg", glm::vec3(0.0f));
  k.translate = in.vec3("translate", glm::vec3(0.0f));
  return k;
}

Deform parse_deform(const json& value, const std::string& where, const std::string& path) {
  if (!value.is_object())
    fail_json_value(where, path, fmt::format("must be an object (got {})", shown(value)));
  const auto kind_it = value.find("kind");
  if (kind_it == value.end()) fail("{}: missing required key '{}'", where, join_path(path, "kind"));
  const std::string kind = kind_it->is_string() ? kind_it->get<std::string>() : std::string();
  Deform d;
  const auto frequency = [&](const JsonObjectReader& in) {
    const float f = in.number("frequency_hz");
    in.require(f > 0.0f, "frequency_hz", "must be positive");
    return f;
  };
  if (kind == "sway") {
    const JsonObjectReader in(value, where, path,
                              {"kind", "amplitude", "frequency_hz", "axis", "phase_per_unit"});
    d.kind = DeformKind::kSway;
    d.amplitude = in.number("amplitude");
    d.frequency_hz = frequency(in);
    const glm::vec3 axis = in.vec3("axis", d.axis);
    in.require(glm::length(axis) > 0.0f, "axis", "must not be zero");
    d.axis = glm::normalize(axis);
    d.phase_per_unit = in.number("phase_per_unit", 0.0f);
  } else if (kind == "twist") {
    const JsonObjectReader in(value, where, path, {"kind", "degrees_per_unit", "frequency_hz"});
    d.kind = DeformKind::kTwist;
    d.degrees_per_unit = in.number("degrees_per_unit");
    d.frequency_hz = frequency(in);
  } else {
    fail_json_value(where, join_path(path, "kind"),
                    fmt::format("must be sway or twist (got {})", shown(*kind_it)));
  }
  return d;
}

}  // namespace

MeshAnimation parse_mesh_animation(const json& value, const std::string& where, const std::string& path) {
  const JsonObjectReader in(value, where, path, {"keys", "deform"});
  MeshAnimation a;
  if (const json* keys = in.get("keys")) {
    if (!keys->is_array() || keys->empty())
      in.fail_key("keys", fmt::format("must be a non-empty array of keys (got {})", shown(*keys)));
    for (size_t i = 0; i < keys->size(); ++i) {
      const std::string key_path = fmt::format("{}[{}]", in.path("keys"), i);
      a.keys.push_back(parse_key((*keys)[i], where, key_path));
      if (i > 0 && !(a.keys[i].time > a.keys[i - 1].time))
        fail("{}: '{}.time' must be greater than the previous key's ({} <= {})", where, key_path,
             a.keys[i].time, a.keys[i - 1].time);
    }
  }
  if (const json* deform = in.get("deform")) {
    if (!deform->is_array())
      in.fail_key("deform", fmt::format("must be an array of deformations (got {})", shown(*deform)));
    for (size_t i = 0; i < deform->size(); ++i)
      a.deforms.push_back(parse_deform((*deform)[i], where, fmt::format("{}[{}]", in.path("deform"), i)));
  }
  if (a.empty()) fail("{}: '{}' needs 'keys' or 'deform'", where, path);
  return a;
}

double parse_scene_animation(const json& value, const std::string& where) {
  const JsonObjectReader in(value, where, "animation", {"fps"});
  const double fps = in.number("fps", float(kDefaultFps));
  in.require(fps > 0.0 && fps <= 10000.0, "fps", "must be in (0, 10000]");
  return fps;
}

bool is_animated(const Scene& scene) {
  return std::any_of(scene.meshes.begin(), scene.meshes.end(),
                     [](const MeshInstance& m) { return !m.animation.empty(); });
}

namespace {

// The lowest object-space y of the vertices the mesh's triangles use (0 for an empty mesh).
double base_height(const TriangleSoup& soup) {
  float lo = std::numeric_limits<float>::max();
  for (const glm::uvec4& t : soup.triangles)
    lo = std::min({lo, soup.positions[t.x].y, soup.positions[t.y].y, soup.positions[t.z].y});
  return soup.triangles.empty() ? 0.0 : soup.anchor.y + double(lo);
}

// Calls f(world position) for every vertex of every mesh at time t, and g(mesh, first vertex, transform)
// once per mesh before its vertices.
template <typename PerMesh, typename PerVertex>
void for_each_posed_vertex(const Scene& scene, double t, PerMesh g, PerVertex f) {
  size_t first = 0;
  for (const MeshInstance& m : scene.meshes) {
    const glm::mat4 transform =
        m.animation.keys.empty() ? m.transform : interpolate_keys(m.animation.keys, t).matrix() * m.transform;
    g(m, first, transform);
    const glm::dmat4 to_world(transform);
    const double base_y = m.animation.deforms.empty() ? 0.0 : base_height(m.soup);
    for (const glm::vec4& q : m.soup.positions) {
      const glm::dvec3 p = deform_point(m.animation.deforms, m.soup.anchor + glm::dvec3(q), base_y, t);
      const glm::dvec4 w = to_world * glm::dvec4(p, 1.0);
      f(glm::dvec3(w) / w.w);
    }
    first += m.soup.positions.size();
  }
}

}  // namespace

void pose_scene(const Scene& scene, double t, const glm::dvec3& anchor, TriangleSoup& out) {
  size_t vertices = 0, triangles = 0;
  for (const MeshInstance& m : scene.meshes) {
    vertices += m.soup.positions.size();
    triangles += m.soup.triangles.size();
  }
  out.anchor = anchor;
  out.positions.resize(vertices);
  out.triangles.resize(triangles);
  size_t v = 0, tri = 0;
  for_each_posed_vertex(
      scene, t,
      [&](const MeshInstance& m, size_t first, const glm::mat4& transform) {
        // A mirroring transform turns counter-clockwise into clockwise: swap two corners to keep normals
        // outward.
        const bool mirrored = glm::determinant(glm::mat3(transform)) < 0.0f;
        for (glm::uvec4 tr : m.soup.triangles) {
          tr.x += uint32_t(first);
          tr.y += uint32_t(first);
          tr.z += uint32_t(first);
          if (m.material != TriangleSoup::kKeepMaterial) tr.w = m.material;
          if (mirrored) std::swap(tr.y, tr.z);
          out.triangles[tri++] = tr;
        }
      },
      [&](const glm::dvec3& w) {
        // Keys and deformations are only checked to be finite numbers: their product may not be.
        if (!(std::abs(w.x) <= text::kMaxCoordinate && std::abs(w.y) <= text::kMaxCoordinate &&
              std::abs(w.z) <= text::kMaxCoordinate))
          fail(
              "{}: the animation at t = {:.4g} s moves a vertex to ({}, {}, {}), beyond the mesh readers' "
              "limit of {:g} (check the keys' and deformations' magnitudes)",
              scene.source, t, w.x, w.y, w.z, text::kMaxCoordinate);
        out.positions[v++] = glm::vec4(glm::vec3(w - anchor), 1.0f);
      });
}

TriangleSoup pose_scene(const Scene& scene, double t, const glm::dvec3& anchor) {
  TriangleSoup out;
  pose_scene(scene, t, anchor, out);
  return out;
}

glm::dvec3 animation_anchor(const Scene& scene) {
  glm::dvec3 lo(std::numeric_limits<double>::max()), hi(-std::numeric_limits<double>::max());
  for_each_posed_vertex(
      scene, 0.0, [](const MeshInstance&, size_t, const glm::mat4&) {},
      [&](const glm::dvec3& w) {
        lo = glm::min(lo, w);
        hi = glm::max(hi, w);
      });
  return lo.x <= hi.x ? choose_anchor(lo, hi) : glm::dvec3(0.0);
}

}  // namespace voxr
