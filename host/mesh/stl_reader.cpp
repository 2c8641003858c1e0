// STL, ASCII and binary. STL lists every triangle's corners; corners at identical positions are merged so
// that a closed mesh is closed by index too (mesh_topology.h).
#include <algorithm>
#include <cstring>

#include "mesh/corner_welder.h"
#include "mesh/mesh_readers.h"
#include "util/text_scan.h"

namespace voxr {

namespace {

// Whether `text` is the ASCII STL keyword `keyword` (lower case) in any case: writers emit `SOLID ...
// ENDSOLID` as well as `solid ... endsolid`.
bool is_keyword(std::string_view text, std::string_view keyword) {
  return text.size() == keyword.size() &&
         std::equal(text.begin(), text.end(), keyword.begin(),
                    [](char a, char b) { return (a >= 'A' && a <= 'Z' ? char(a - 'A' + 'a') : a) == b; });
}

bool looks_ascii(std::string_view bytes) {
  size_t i = 0;
  while (i < bytes.size() && (text::is_space(bytes[i]) || bytes[i] == '\n')) ++i;
  if (!is_keyword(bytes.substr(i, 5), "solid")) return false;
  const size_t eol = bytes.find('\n', i);
  if (eol == std::string_view::npos) return bytes.size() < 84;  // a one-line file is no binary STL either
  i = eol + 1;
  while (i < bytes.size() && (text::is_space(bytes[i]) || bytes[i] == '\n')) ++i;
  return is_keyword(bytes.substr(i, 5), "facet") || is_keyword(bytes.substr(i, 8), "endsolid");
}

PolygonMesh read_binary(const std::string& name, std::string_view bytes, uint32_t triangles) {
  PolygonMesh mesh;
  CornerWelder welder(mesh, size_t(triangles) / 2);  // a closed mesh has about T/2 vertices
  mesh.indices.reserve(3 * size_t(triangles));
  mesh.face_sizes.assign(triangles, 3);
  for (uint32_t t = 0; t < triangles; ++t) {
    // Per triangle: normal (3 floats), 3 corners (9 floats), 2 attribute bytes.
    float c[9];
    std::memcpy(c, bytes.data() + 84 + 50 * size_t(t) + 12, sizeof c);
    for (int k = 0; k < 3; ++k) {
      const glm::dvec3 p(c[3 * k], c[3 * k + 1], c[3 * k + 2]);
      if (!(std::abs(p.x) <= text::kMaxCoordinate && std::abs(p.y) <= text::kMaxCoordinate &&
            std::abs(p.z) <= text::kMaxCoordinate))
        fail("{}: triangle {} corner {} is not finite ({}, {}, {})", name, t, k, p.x, p.y, p.z);
      mesh.indices.push_back(welder.add(p));
    }
  }
  return mesh;
}

PolygonMesh read_ascii(const std::string& name, std::string_view bytes) {
  PolygonMesh mesh;
  CornerWelder welder(mesh, bytes.size() / 500);  // about 250 bytes of text per triangle
  text::Lines lines(bytes);
  std::string_view line;
  std::vector<std::string_view> tokens;
  std::vector<uint32_t> loop;
  size_t number = 0, loop_line = 0;
  bool in_loop = false;
  while (lines.next(line, number)) {
    text::split(line, 0, tokens);
    if (tokens.empty()) continue;
    if (is_keyword(tokens[0], "outer")) {
      if (in_loop) fail("{}: line {}: 'outer loop' inside the loop of line {}", name, number, loop_line);
      in_loop = true;
      loop_line = number;
      loop.clear();
    } else if (is_keyword(tokens[0], "vertex")) {
      if (!in_loop) fail("{}: line {}: a vertex outside 'outer loop' ... 'endloop'", name, number);
      loop.push_back(welder.add(text::parse_vertex(name, number, tokens)));
    } else if (is_keyword(tokens[0], "endloop")) {
      if (!in_loop) fail("{}: line {}: 'endloop' without 'outer loop'", name, number);
      in_loop = false;
      mesh.add_face(loop.data(), uint32_t(loop.size()));
    }
  }
  if (in_loop) fail("{}: the file ends inside the loop that starts on line {}", name, loop_line);
  return mesh;
}

}  // namespace

PolygonMesh read_stl(const std::string& name, std::string_view bytes, std::vector<std::string>& notes) {
  uint32_t triangles = 0;
  if (bytes.size() >= 84) std::memcpy(&triangles, bytes.data() + 80, 4);
  const uint64_t binary_size = 84 + 50 * uint64_t(triangles);
  if (bytes.size() >= 84 && bytes.size() == binary_size) return read_binary(name, bytes, triangles);
  if (looks_ascii(bytes)) return read_ascii(name, bytes);
  if (bytes.size() < 84)
    fail("{}: neither ASCII STL (no 'solid' ... 'facet') nor binary STL (shorter than the 84-byte header)",
         name);
  if (bytes.size() < binary_size)
    fail("{}: binary STL header announces {} triangles ({} bytes) but the file has {} bytes", name, triangles,
         binary_size, bytes.size());
  // Some exporters pad or append a footer; the header's count is the authority.
  notes.push_back(fmt::format("{}: ignored {} bytes after the {} triangles the binary STL header announces",
                              name, bytes.size() - binary_size, triangles));
  return read_binary(name, bytes, triangles);
}

}  // namespace voxr
