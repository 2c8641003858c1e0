#include "mesh/polygon_triangulation.h"

#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Constrained_triangulation_face_base_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_face_base_with_info_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <list>
#include <stdexcept>

namespace voxr {

namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using VertexBase = CGAL::Triangulation_vertex_base_with_info_2<uint32_t, K>;
using FaceInfo = CGAL::Triangulation_face_base_with_info_2<int, K>;  // nesting level, -1 while unknown
using FaceBase = CGAL::Constrained_triangulation_face_base_2<K, FaceInfo>;
using Tds = CGAL::Triangulation_data_structure_2<VertexBase, FaceBase>;
// Crossing constraints throw: crossings are found before CGAL sees the polygon, so a throw is a near-miss.
using Cdt = CGAL::Constrained_Delaunay_triangulation_2<K, Tds, CGAL::No_constraint_intersection_tag>;

// Nesting level of each face: 0 outside, 1 inside the boundary, 2 inside a hole ... (CGAL's
// Polygon_triangulation example): flood each region, crossing a constrained edge adds one.
void mark_nesting(Cdt& cdt) {
  for (Cdt::Face_handle f : cdt.all_face_handles()) f->info() = -1;
  std::list<Cdt::Edge> border;
  auto flood = [&](Cdt::Face_handle start, int level) {
    std::list<Cdt::Face_handle> queue{start};
    while (!queue.empty()) {
      const Cdt::Face_handle f = queue.front();
      queue.pop_front();
      if (f->info() != -1) continue;
      f->info() = level;
      for (int i = 0; i < 3; ++i) {
        const Cdt::Face_handle n = f->neighbor(i);
        if (n->info() != -1) continue;
        if (cdt.is_constrained(Cdt::Edge(f, i))) {
          border.push_back(Cdt::Edge(f, i));
        } else {
          queue.push_back(n);
        }
      }
    }
  };
  flood(cdt.infinite_face(), 0);
  while (!border.empty()) {
    const Cdt::Edge e = border.front();
    border.pop_front();
    const Cdt::Face_handle n = e.first->neighbor(e.second);
    if (n->info() == -1) flood(n, e.first->info() + 1);
  }
}

double cross2(const glm::dvec2& a, const glm::dvec2& b) {
  return a.x * b.y - a.y * b.x;
}

// Proper or touching intersection of segments ab and cd (2-D, exact enough for a warning's decision).
bool segments_meet(const glm::dvec2& a, const glm::dvec2& b, const glm::dvec2& c, const glm::dvec2& d) {
  const double d1 = cross2(b - a, c - a), d2 = cross2(b - a, d - a);
  const double d3 = cross2(d - c, a - c), d4 = cross2(d - c, b - c);
  if (((d1 > 0 && d2 < 0) || (d1 < 0 && d2 > 0)) && ((d3 > 0 && d4 < 0) || (d3 < 0 && d4 > 0))) return true;
  auto on = [](const glm::dvec2& p, const glm::dvec2& q, const glm::dvec2& r, double side) {
    return side == 0 && std::min(p.x, q.x) <= r.x && r.x <= std::max(p.x, q.x) && std::min(p.y, q.y) <= r.y &&
           r.y <= std::max(p.y, q.y);
  };
  return on(a, b, c, d1) || on(a, b, d, d2) || on(c, d, a, d3) || on(c, d, b, d4);
}

bool self_intersecting(const std::vector<glm::dvec2>& p) {
  const size_t n = p.size();
  for (size_t i = 0; i < n; ++i)
    for (size_t j = i + 1; j < n; ++j) {
      if (p[i] == p[j]) return true;
      const bool adjacent = j == i + 1 || (i == 0 && j == n - 1);
      if (!adjacent && segments_meet(p[i], p[(i + 1) % n], p[j], p[(j + 1) % n])) return true;
    }
  return false;
}

// Every turn goes the same way (collinear corners allowed) and the boundary winds once.
bool convex(const std::vector<glm::dvec2>& p) {
  const size_t n = p.size();
  double turning = 0.0;
  for (size_t i = 0; i < n; ++i) {
    const glm::dvec2 e0 = p[(i + 1) % n] - p[i], e1 = p[(i + 2) % n] - p[(i + 1) % n];
    if (cross2(e0, e1) < 0) return false;
    turning += std::atan2(cross2(e0, e1), glm::dot(e0, e1));
  }
  return turning < 2.0 * M_PI + 1e-6;
}

constexpr uint32_t kPairwiseCorners = 256;

}  // namespace

std::vector<std::string> TriangulationReport::warnings(const std::string& source) const {
  std::vector<std::string> out;
  if (nonplanar)
    out.push_back(
        fmt::format("{}: {} polygon faces are not planar (first: face {}); they were triangulated on "
                    "their best-fit plane",
                    source, nonplanar, first_nonplanar));
  if (self_intersecting)
    out.push_back(
        fmt::format("{}: {} polygon faces cross themselves or repeat a corner (first: face {}); they "
                    "were fanned from their first corner",
                    source, self_intersecting, first_self_intersecting));
  if (too_small)
    out.push_back(fmt::format("{}: {} faces have fewer than 3 corners and were dropped", source, too_small));
  return out;
}

void triangulate(const PolygonMesh& mesh, HostArray<glm::uvec4>& out, TriangulationReport& report,
                 HostArray<uint32_t>* looks) {
  // Each face's look for every triangle the face appended (faces append in order, in their own iteration).
  const bool with_looks = looks != nullptr && !mesh.face_looks.empty();
  size_t looked = out.size();
  auto look_up_to = [&](size_t face) {
    if (!with_looks) return;
    looks->resize(looks->size() + (out.size() - looked), mesh.face_looks[face]);
    looked = out.size();
  };
  const std::vector<glm::dvec3>& pos = mesh.positions;
  // The common case, a mesh of triangles only, in one pass with no per-face work.
  if (mesh.indices.size() == 3 * mesh.face_sizes.size() &&
      std::all_of(mesh.face_sizes.begin(), mesh.face_sizes.end(), [](uint32_t n) { return n == 3; })) {
    const size_t first = out.size();
    out.resize(first + mesh.face_sizes.size());
    const uint32_t* c = mesh.indices.data();
    for (size_t f = 0; f < mesh.face_sizes.size(); ++f, c += 3)
      out[first + f] = glm::uvec4(c[0], c[1], c[2], mesh.materials.empty() ? 0u : mesh.materials[f]);
    if (with_looks) looks->insert(looks->end(), mesh.face_looks.begin(), mesh.face_looks.end());
    return;
  }
  std::vector<glm::dvec2> plane;
  size_t at = 0;
  for (size_t f = 0; f < mesh.face_sizes.size(); ++f) {
    if (f > 0) look_up_to(f - 1);
    const uint32_t n = mesh.face_sizes[f];
    const uint32_t* c = mesh.indices.data() + at;
    at += n;
    const uint32_t material = mesh.materials.empty() ? 0u : mesh.materials[f];
    if (n < 3) {
      ++report.too_small;
      continue;
    }
    auto fan = [&] {
      for (uint32_t k = 1; k + 1 < n; ++k) out.push_back(glm::uvec4(c[0], c[k], c[k + 1], material));
    };
    if (n == 3) {
      fan();
      continue;
    }
    ++report.polygons;
    // Newell's normal and a frame of its plane, relative to the first corner (keeps far coordinates exact).
    const glm::dvec3 origin = pos[c[0]];
    glm::dvec3 normal(0.0), centre(0.0);
    for (uint32_t k = 0; k < n; ++k) {
      const glm::dvec3 a = pos[c[k]] - origin, b = pos[c[(k + 1) % n]] - origin;
      normal += glm::dvec3((a.y - b.y) * (a.z + b.z), (a.z - b.z) * (a.x + b.x), (a.x - b.x) * (a.y + b.y));
      centre += a;
    }
    double length = glm::length(normal);
    if (!(length > 0.0)) {
      // Lobes of opposite winding cancel (a bow tie): take the plane from the largest corner triangle.
      for (uint32_t k = 1; k + 1 < n; ++k) {
        const glm::dvec3 cross = glm::cross(pos[c[k]] - origin, pos[c[k + 1]] - origin);
        if (glm::length(cross) > length) {
          normal = cross;
          length = glm::length(cross);
        }
      }
    }
    if (!(length > 0.0)) {  // all corners on a line: no area either way
      fan();
      continue;
    }
    normal /= length;
    centre /= double(n);
    const glm::dvec3 u = glm::normalize(std::abs(normal.x) < 0.9 ? glm::cross(normal, glm::dvec3(1, 0, 0))
                                                                 : glm::cross(normal, glm::dvec3(0, 1, 0)));
    const glm::dvec3 v = glm::cross(normal, u);
    plane.resize(n);
    double size = 0.0, off_plane = 0.0;
    for (uint32_t k = 0; k < n; ++k) {
      const glm::dvec3 d = pos[c[k]] - origin - centre;
      plane[k] = glm::dvec2(glm::dot(d, u), glm::dot(d, v));
      size = std::max(size, glm::length(d));
      off_plane = std::max(off_plane, std::abs(glm::dot(d, normal)));
    }
    if (off_plane > 1e-3 * size && report.nonplanar++ == 0) report.first_nonplanar = f;
    // The pairwise crossing test is quadratic: above kPairwiseCorners, CGAL's insertion finds crossings
    // instead (it throws on crossing constraints), so a 100 k-corner face costs n log n, not n^2.
    if (n <= kPairwiseCorners && self_intersecting(plane)) {
      if (report.self_intersecting++ == 0) report.first_self_intersecting = f;
      fan();
      continue;
    }
    if (convex(plane)) {
      fan();
      continue;
    }
    ++report.concave;
    Cdt cdt;
    std::vector<Cdt::Vertex_handle> vertices(n);
    for (uint32_t k = 0; k < n; ++k) {
      vertices[k] = cdt.insert(K::Point_2(plane[k].x, plane[k].y));
      vertices[k]->info() = c[k];
    }
    try {
      // A repeated corner position merges two vertices (their indices would be lost): a degenerate boundary.
      if (cdt.number_of_vertices() != n) throw std::runtime_error("repeated corner");
      for (uint32_t k = 0; k < n; ++k) cdt.insert_constraint(vertices[k], vertices[(k + 1) % n]);
    } catch (const std::exception&) {  // a crossing too close to call above, or of a face too large for it
      if (report.self_intersecting++ == 0) report.first_self_intersecting = f;
      fan();
      continue;
    }
    mark_nesting(cdt);
    for (Cdt::Face_handle t : cdt.finite_face_handles())
      if (t->info() % 2 == 1)
        out.push_back(glm::uvec4(t->vertex(0)->info(), t->vertex(1)->info(), t->vertex(2)->info(), material));
  }
  if (!mesh.face_sizes.empty()) look_up_to(mesh.face_sizes.size() - 1);
}

}  // namespace voxr
