#include "core/mesh_loader.h"

#include <algorithm>
#include <cctype>
#include <cmath>

#include "mesh/assimp_reader.h"
#include "mesh/file_bytes.h"
#include "mesh/mesh_readers.h"
#include "mesh/polygon_triangulation.h"
#include "util/error.h"
#include "util/file_extension.h"

namespace voxr {

namespace {

using Reader = PolygonMesh (*)(const std::string& name, std::string_view bytes,
                               std::vector<std::string>& notes);

struct Format {
  const char* extension;
  Reader read;
};

// voxr's own readers, in double precision (mesh_readers.h); Assimp reads the rest (assimp_reader.h).
const Format kFormats[] = {
    {".obj", [](const std::string& n, std::string_view b,
                std::vector<std::string>& notes) { return read_obj(n, b, &notes); }},
    {".off",
     [](const std::string& n, std::string_view b, std::vector<std::string>&) { return read_off(n, b); }},
    {".ply",
     [](const std::string& n, std::string_view b, std::vector<std::string>&) { return read_ply(n, b); }},
    {".stl", read_stl},
};

const Format* find_format(const std::filesystem::path& file) {
  const std::string ext = lower_extension(file);
  for (const Format& f : kFormats)
    if (ext == f.extension) return &f;
  return nullptr;
}

// The soup of `mesh`: positions relative to an anchor chosen for the vertices the faces use, in double
// until then; faces triangulated; the mesh's colours, looks and textures moved into the soup's colors.
TriangleSoup to_soup(PolygonMesh& mesh, TriangulationReport& report) {
  // Which vertices faces use (a bit each: sequential over the indices), then their bounds in order.
  std::vector<bool> used(mesh.positions.size(), false);
  for (uint32_t i : mesh.indices) used[i] = true;
  glm::dvec3 lo(std::numeric_limits<double>::max()), hi(-std::numeric_limits<double>::max());
  for (size_t i = 0; i < mesh.positions.size(); ++i)
    if (used[i]) {
      lo = glm::min(lo, mesh.positions[i]);
      hi = glm::max(hi, mesh.positions[i]);
    }
  TriangleSoup soup;
  soup.anchor = mesh.indices.empty() ? glm::dvec3(0.0) : choose_anchor(lo, hi);
  soup.positions.resize(mesh.positions.size());
  for (size_t i = 0; i < mesh.positions.size(); ++i)
    soup.positions[i] = glm::vec4(glm::vec3(mesh.positions[i] - soup.anchor), 1.0f);
  soup.triangles.reserve(mesh.indices.size() - 2 * std::min(mesh.indices.size(), mesh.face_sizes.size()));
  SoupColors& colors = soup.colors;
  triangulate(mesh, soup.triangles, report, &colors.triangle_look);
  colors.vertex_rgba.assign(mesh.vertex_rgba.begin(), mesh.vertex_rgba.end());
  colors.vertex_uv.assign(mesh.vertex_uv.begin(), mesh.vertex_uv.end());
  colors.looks = std::move(mesh.looks);
  colors.textures = std::move(mesh.textures);
  return soup;
}

}  // namespace

std::string mesh_extensions() {
  std::string s;
  for (const Format& f : kFormats) s += (s.empty() ? "" : ", ") + std::string(f.extension);
  for (const char* e : kAssimpExtensions) s += ", " + std::string(e);
  return s;
}

bool is_mesh_file(const std::filesystem::path& file) {
  return find_format(file) != nullptr || is_assimp_extension(file);
}

TriangleSoup load_mesh(const std::filesystem::path& file, std::vector<std::string>* warnings) {
  const std::string name = file.string();
  const Format* format = find_format(file);
  if (!format && !is_assimp_extension(file))
    fail("{}: unsupported mesh format '{}' (supported: {})", name, file.extension().string(),
         mesh_extensions());
  std::error_code ec;
  const auto status = std::filesystem::status(file, ec);
  if (!std::filesystem::exists(status)) fail("{}: no such file", name);
  if (std::filesystem::is_directory(status)) fail("{}: is a directory, not a mesh file", name);

  std::vector<std::string> notes;
  PolygonMesh mesh;
  if (format) {
    const FileBytes data(file);
    if (data.view().empty()) fail("{}: the file is empty", name);
    mesh = format->read(name, data.view(), notes);
  } else {
    mesh = read_with_assimp(file);
  }
  TriangulationReport report;
  TriangleSoup soup = to_soup(mesh, report);
  if (soup.triangles.empty()) {
    if (mesh.face_count() > 0)
      fail("{}: no triangles: all {} faces have fewer than 3 vertices", name, mesh.face_count());
    fail("{}: no triangles found", name);
  }
  // No validate_soup here: the readers have checked every index against the vertices and every
  // coordinate (finite, at most 1e30), which is what it checks; callers validate what they assemble.
  if (warnings) {
    warnings->insert(warnings->end(), notes.begin(), notes.end());
    for (std::string& w : report.warnings(name)) warnings->push_back(std::move(w));
  }
  return soup;
}

TriangleSoup soup_from_arrays(std::span<const double> positions, std::span<const uint32_t> triangles,
                              std::span<const uint32_t> materials, const std::string& name) {
  if (positions.size() % 3) fail("{}: {} position values are not x, y, z triples", name, positions.size());
  if (triangles.size() % 3) fail("{}: {} triangle indices are not triples", name, triangles.size());
  if (triangles.empty()) fail("{}: no triangles", name);
  const size_t vertices = positions.size() / 3, count = triangles.size() / 3;
  if (!materials.empty() && materials.size() != count)
    fail("{}: {} material ids for {} triangles", name, materials.size(), count);
  PolygonMesh mesh;
  mesh.positions.resize(vertices);
  for (size_t v = 0; v < vertices; ++v) {
    const glm::dvec3 p(positions[3 * v], positions[3 * v + 1], positions[3 * v + 2]);
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
      fail("{}: vertex {} is not finite ({}, {}, {})", name, v, p.x, p.y, p.z);
    mesh.positions[v] = p;
  }
  for (size_t i = 0; i < triangles.size(); ++i)
    if (triangles[i] >= vertices)
      fail("{}: triangle {} uses vertex {}, but there are {} vertices", name, i / 3, triangles[i], vertices);
  mesh.indices.assign(triangles.begin(), triangles.end());
  mesh.face_sizes.assign(count, 3u);
  mesh.materials.assign(materials.begin(), materials.end());
  TriangulationReport report;
  return to_soup(mesh, report);
}

}  // namespace voxr
