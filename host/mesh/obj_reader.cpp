// Wavefront OBJ: positions from `v`, polygons from `f`, material ids from `usemtl`; texture coordinates,
// normals, groups, material libraries, lines and points carry no area and are ignored.
#include <algorithm>
#include <map>

#include "mesh/mesh_readers.h"
#include "util/text_scan.h"

namespace voxr {

namespace {

using text::printable;

// One corner of a face, "v", "v/vt", "v//vn" or "v/vt/vn", with 1-based or negative (relative) indices.
uint32_t corner_index(const std::string& name, size_t line, std::string_view token, size_t vertices) {
  const std::string_view v = token.substr(0, token.find('/'));
  long long index = 0;
  const auto [end, ec] = std::from_chars(v.data(), v.data() + v.size(), index);
  if (ec != std::errc() || end != v.data() + v.size() || v.empty())
    fail("{}: line {}: face corner '{}' does not start with a vertex index", name, line, printable(token));
  const long long resolved = index < 0 ? (long long)vertices + index : index - 1;
  if (index == 0 || resolved < 0 || resolved >= (long long)vertices)
    fail("{}: line {}: face corner '{}' refers to vertex {} but {} vertices are defined before it", name,
         line, printable(token), index, vertices);
  return uint32_t(resolved);
}

}  // namespace

PolygonMesh read_obj(const std::string& name, std::string_view bytes) {
  PolygonMesh mesh;
  text::Lines lines(bytes);
  std::string_view line;
  std::vector<std::string_view> tokens;
  std::vector<uint32_t> corners;
  // Material ids in order of first use by a face: the faces before any `usemtl` (or after a bare `usemtl`)
  // form the group named "", counted like any other.
  std::map<std::string, uint32_t, std::less<>> ids;
  std::string_view group;
  size_t number = 0;
  while (lines.next(line, number)) {
    text::split(line, '#', tokens);
    if (tokens.empty()) continue;
    if (tokens[0] == "v") {
      const glm::dvec3 p = text::parse_vertex(name, number, tokens);
      if (mesh.positions.size() >= (size_t(1) << 31))
        fail("{}: line {}: more vertices than voxr can index", name, number);
      mesh.positions.push_back(p);
    } else if (tokens[0] == "f" || tokens[0] == "fo") {
      corners.clear();
      for (size_t k = 1; k < tokens.size(); ++k)
        corners.push_back(corner_index(name, number, tokens[k], mesh.positions.size()));
      mesh.add_face(corners.data(), uint32_t(corners.size()));
      auto id = ids.find(group);
      if (id == ids.end()) id = ids.emplace(std::string(group), uint32_t(ids.size())).first;
      mesh.materials.push_back(id->second);
    } else if (tokens[0] == "usemtl") {
      // The name is the rest of the statement (names may hold spaces).
      group = tokens.size() > 1
                  ? std::string_view(tokens[1].data(),
                                     tokens.back().data() + tokens.back().size() - tokens[1].data())
                  : std::string_view();
    }
  }
  if (ids.size() <= 1) mesh.materials.clear();  // one material: every face has id 0
  return mesh;
}

}  // namespace voxr
