// Wavefront OBJ: positions from `v`, polygons from `f`, material ids from `usemtl`; surface colour from
// `v x y z r g b` (vertex colours in [0, 1]), `vt` (texture coordinates) and the material libraries that
// `mtllib` names (`Kd`, `d`/`Tr`, `map_Kd`). Normals, groups, lines and points carry no area or colour and
// are ignored.
#include <algorithm>
#include <filesystem>
#include <map>
#include <unordered_map>

#include "mesh/file_bytes.h"
#include "mesh/mesh_readers.h"
#include "mesh/texture_reader.h"
#include "util/text_scan.h"

namespace voxr {

namespace {

namespace fs = std::filesystem;
using text::printable;

// resolve_index for every index its fast path does not take: std::from_chars decides, as it always has;
// fails naming the line when the index is not an integer or is out of range.
[[gnu::noinline]] uint32_t resolve_index_slow(const std::string& name, size_t line, std::string_view token,
                                              std::string_view index, size_t count, const char* what,
                                              const char* whats) {
  long long value = 0;
  const auto [end, ec] = std::from_chars(index.data(), index.data() + index.size(), value);
  if (ec != std::errc() || end != index.data() + index.size() || index.empty())
    fail("{}: line {}: face corner '{}' {} {} index", name, line, printable(token),
         std::string_view(what) == "vertex" ? "does not start with a" : "has no valid", what);
  const long long resolved = value < 0 ? (long long)count + value : value - 1;
  if (value == 0 || resolved < 0 || resolved >= (long long)count)
    fail("{}: line {}: face corner '{}' refers to {} {} but {} {} are defined before it", name, line,
         printable(token), what, value, count, whats);
  return uint32_t(resolved);
}

// A 1-based or negative (relative) index of `what` (vertex, texture coordinate; `whats` its plural) resolved
// against `count`. The common case, 1 to 9 digits in range, is parsed here (a digit loop, inlined into the
// face loop; from_chars<long long> stopped being inlined there once the reader read colour); anything else
// goes to resolve_index_slow.
inline uint32_t resolve_index(const std::string& name, size_t line, std::string_view token,
                              std::string_view index, size_t count, const char* what, const char* whats) {
  const bool negative = !index.empty() && index[0] == '-';
  const size_t digits = index.size() - negative;
  if (digits >= 1 && digits <= 9) {
    long long value = 0;
    size_t i = negative;
    for (; i < index.size() && uint8_t(index[i] - '0') < 10; ++i) value = value * 10 + (index[i] - '0');
    if (i == index.size()) {
      const long long resolved = negative ? (long long)count - value : value - 1;
      if (value != 0 && resolved >= 0 && resolved < (long long)count) return uint32_t(resolved);
    }
  }
  return resolve_index_slow(name, line, token, index, count, what, whats);
}

constexpr int32_t kNoUv = -1;

// A colour component in [0, 1], as a byte; fails naming the line.
uint32_t unit_component(const std::string& name, size_t line, std::string_view token, const char* what) {
  double v = 0.0;
  if (!text::parse_number(token, v) || v < 0.0 || v > 1.0)
    fail("{}: line {}: {} '{}' is not a number in [0, 1]", name, line, what, printable(token));
  return unit_to_byte(v);
}

// The rest of a statement from tokens[first] on, spaces included (names and paths may hold them).
std::string_view rest_of(const std::vector<std::string_view>& tokens, size_t first) {
  if (tokens.size() <= first) return {};
  return std::string_view(tokens[first].data(),
                          tokens.back().data() + tokens.back().size() - tokens[first].data());
}

struct ObjMaterial {
  SurfaceLook look;
  bool coloured = false;  // Kd, d, Tr or map_Kd given
};

// Reads the material library `file` into `materials` (later definitions of a name replace earlier ones);
// textures are read relative to the library's folder, each file once (`texture_ids`).
void read_mtl(const fs::path& file, std::map<std::string, ObjMaterial, std::less<>>& materials,
              std::vector<SoupTexture>& textures, std::map<fs::path, int32_t>& texture_ids) {
  const std::string name = file.string();
  const FileBytes bytes(file);
  text::Lines lines(bytes.view());
  std::string_view line;
  std::vector<std::string_view> tokens;
  size_t number = 0;
  ObjMaterial* current = nullptr;
  auto need_material = [&](std::string_view statement) {
    if (!current) fail("{}: line {}: '{}' before any newmtl", name, number, printable(statement));
  };
  while (lines.next(line, number)) {
    text::split(line, '#', tokens);
    if (tokens.empty()) continue;
    const std::string_view key = tokens[0];
    if (key == "newmtl") {
      current = &materials[std::string(rest_of(tokens, 1))];
      *current = ObjMaterial();
    } else if (key == "Kd") {
      need_material(key);
      if (tokens.size() != 2 && tokens.size() != 4)
        fail("{}: line {}: Kd reads 'Kd r g b' (numbers in [0, 1])", name, number);
      uint32_t rgb[3];
      for (int c = 0; c < 3; ++c)
        rgb[c] = unit_component(name, number, tokens[tokens.size() == 2 ? 1 : 1 + c], "Kd component");
      current->look.factor_rgba = pack_rgba(rgb[0], rgb[1], rgb[2], current->look.factor_rgba >> 24);
      current->coloured = true;
    } else if (key == "d" || key == "Tr") {
      need_material(key);
      // "d -halo 0.5" is the one option of d; its halo has no meaning for a base colour.
      const std::string_view value = tokens.back();
      if (tokens.size() < 2) fail("{}: line {}: {} needs a value in [0, 1]", name, number, key);
      const uint32_t a = unit_component(name, number, value, key == "d" ? "dissolve d" : "transparency Tr");
      current->look.factor_rgba = (current->look.factor_rgba & 0x00ffffffu) | (key == "d" ? a : 255 - a)
                                                                                  << 24;
      current->coloured = true;
    } else if (key == "map_Kd") {
      need_material(key);
      if (tokens.size() < 2) fail("{}: line {}: map_Kd needs a texture file", name, number);
      if (tokens[1].size() > 1 && tokens[1][0] == '-')
        fail(
            "{}: line {}: map_Kd option '{}' is not supported (voxr samples the whole texture with "
            "wrap-around; remove the option)",
            name, number, printable(tokens[1]));
      std::string path(rest_of(tokens, 1));
      std::replace(path.begin(), path.end(), '\\', '/');  // files written on Windows
      const fs::path texture = file.parent_path() / path;
      auto [it, inserted] = texture_ids.try_emplace(texture, int32_t(textures.size()));
      if (inserted) textures.push_back(read_texture(texture, name, number));
      current->look.texture = it->second;
      current->coloured = true;
    }
  }
}

// Gives every vertex one texture coordinate: a vertex whose corners carry different `vt` indices is split,
// its first index keeping the vertex and each other one a copy (position and colour) appended at the end.
void split_uv_corners(const std::string& name, PolygonMesh& mesh, const std::vector<int32_t>& corner_uv,
                      const std::vector<glm::vec2>& uvs) {
  const size_t original = mesh.positions.size();
  constexpr int32_t kUnset = -2;
  std::vector<int32_t> first(original, kUnset);
  mesh.vertex_uv.assign(original, glm::vec2(0.0f));
  std::unordered_map<uint64_t, uint32_t> copies;
  for (size_t i = 0; i < mesh.indices.size(); ++i) {
    const uint32_t v = mesh.indices[i];
    const int32_t t = corner_uv.empty() ? kNoUv : corner_uv[i];
    if (first[v] == kUnset) {
      first[v] = t;
      if (t >= 0) mesh.vertex_uv[v] = uvs[size_t(t)];
      continue;
    }
    if (first[v] == t) continue;
    const uint64_t key = uint64_t(v) << 32 | uint32_t(t);
    const auto [it, inserted] = copies.try_emplace(key, uint32_t(mesh.positions.size()));
    if (inserted) {
      if (mesh.positions.size() >= (size_t(1) << 31))
        fail("{}: more vertices than voxr can index after splitting them at texture seams", name);
      mesh.positions.push_back(mesh.positions[v]);
      if (!mesh.vertex_rgba.empty()) mesh.vertex_rgba.push_back(mesh.vertex_rgba[v]);
      mesh.vertex_uv.push_back(t >= 0 ? uvs[size_t(t)] : glm::vec2(0.0f));
    }
    mesh.indices[i] = it->second;
  }
}

}  // namespace

namespace {

// What an OBJ file says about surface colour, besides vertex colours: texture coordinates, each corner's
// (allocated at the first corner with one), and the materials of the libraries. Its functions are out of
// line so that read_obj's loop over `v` and `f` lines stays as small as it was without colour: with them in
// it, GCC stopped inlining text::split and from_chars there and bunny.obj read ~25 % slower.
struct ObjColours {
  const std::string& name;
  std::vector<std::string>* notes;
  std::vector<glm::vec2> uvs;
  std::vector<int32_t> corner_uv;
  bool any_corner_uv = false;  // corner_uv is filled from the first corner with a vt on
  std::map<std::string, ObjMaterial, std::less<>> materials;
  std::vector<SoupTexture> textures;
  std::map<fs::path, int32_t> texture_ids;

  [[gnu::noinline]] void vertex_colour(PolygonMesh& mesh, size_t number,
                                       const std::vector<std::string_view>& tokens) {
    if (tokens.size() == 7) {  // v x y z r g b
      if (mesh.vertex_rgba.empty()) mesh.vertex_rgba.assign(mesh.positions.size(), kWhiteRgba);
      uint32_t rgb[3];
      for (int c = 0; c < 3; ++c) rgb[c] = unit_component(name, number, tokens[4 + c], "vertex colour");
      mesh.vertex_rgba.push_back(pack_rgba(rgb[0], rgb[1], rgb[2]));
    } else if (!mesh.vertex_rgba.empty()) {
      mesh.vertex_rgba.push_back(kWhiteRgba);
    }
  }

  [[gnu::noinline]] void texture_coordinate(size_t number, const std::vector<std::string_view>& tokens) {
    if (tokens.size() < 2) fail("{}: line {}: a texture coordinate needs u (and v)", name, number);
    glm::dvec2 uv(0.0);
    for (size_t c = 0; c < 2 && c + 1 < tokens.size(); ++c)
      if (!text::parse_number(tokens[c + 1], uv[c]))
        fail("{}: line {}: texture coordinate '{}' is not a finite number", name, number,
             printable(tokens[c + 1]));
    uvs.push_back(glm::vec2(uv));
  }

  // The texture coordinates of a face's corners (after the face's corners were added to mesh.indices).
  [[gnu::noinline]] void corner_uvs(const PolygonMesh& mesh, size_t number,
                                    const std::vector<std::string_view>& tokens) {
    const size_t first = mesh.indices.size() - (tokens.size() - 1);
    for (size_t k = 1; k < tokens.size(); ++k) {
      const std::string_view token = tokens[k];
      const size_t slash = token.find('/');
      const std::string_view rest =
          slash == std::string_view::npos ? std::string_view() : token.substr(slash + 1);
      const std::string_view vt = rest.substr(0, rest.find('/'));
      const int32_t uv = vt.empty() ? kNoUv
                                    : int32_t(resolve_index(name, number, token, vt, uvs.size(),
                                                            "texture coordinate", "texture coordinates"));
      if (uv != kNoUv && !any_corner_uv) {
        corner_uv.assign(first + k - 1, kNoUv);
        any_corner_uv = true;
      }
      if (any_corner_uv) corner_uv.push_back(uv);
    }
  }

  // `mtllib`: the rest of the line names one library (file names with spaces are common) or, when no such
  // file exists, several separated by spaces (the format's definition).
  [[gnu::noinline]] void material_libraries(size_t number, const std::vector<std::string_view>& tokens) {
    std::vector<std::string> libraries{std::string(rest_of(tokens, 1))};
    std::error_code ec;
    auto path_of = [&](std::string library) {
      std::replace(library.begin(), library.end(), '\\', '/');
      return fs::path(name).parent_path() / library;
    };
    if (!fs::is_regular_file(path_of(libraries[0]), ec) && tokens.size() > 2)
      libraries.assign(tokens.begin() + 1, tokens.end());
    for (const std::string& library : libraries) {
      if (library.empty() || !fs::is_regular_file(path_of(library), ec)) {
        if (notes)
          notes->push_back(
              fmt::format("{}: line {}: material library '{}' not found; its materials are white", name,
                          number, printable(library)));
        continue;
      }
      read_mtl(path_of(library), materials, textures, texture_ids);
    }
  }

  // Looks: one per material id, from the library's material of that name (white when it has none); none at
  // all when no material has a colour.
  [[gnu::noinline]] void finish(PolygonMesh& mesh, const std::map<std::string, uint32_t, std::less<>>& ids) {
    std::vector<SurfaceLook> looks(ids.size());
    bool looks_coloured = false, textured = false;
    for (const auto& [material, id] : ids) {
      const auto m = materials.find(material);
      if (m == materials.end()) {
        if (notes && !material.empty() && !materials.empty())
          notes->push_back(fmt::format("{}: material '{}' is in no material library; it is white", name,
                                       printable(material)));
        continue;
      }
      looks[id] = m->second.look;
      looks_coloured |= m->second.coloured;
      textured |= m->second.look.texture >= 0;
    }
    if (!looks_coloured) return;
    mesh.looks = std::move(looks);
    if (mesh.looks.size() > 1) mesh.face_looks = mesh.materials;
    // Every texture of the libraries is kept (looks index them as the libraries do); UVs only matter,
    // and vertices are only split for them, when a face's material has one.
    if (textured) {
      mesh.textures = std::move(textures);
      split_uv_corners(name, mesh, corner_uv, uvs);
    }
  }
};

}  // namespace

PolygonMesh read_obj(const std::string& name, std::string_view bytes, std::vector<std::string>* notes) {
  PolygonMesh mesh;
  text::Lines lines(bytes);
  std::string_view line;
  std::vector<std::string_view> tokens;
  std::vector<uint32_t> corners;
  // Material ids in order of first use by a face: the faces before any `usemtl` (or after a bare `usemtl`)
  // form the group named "", counted like any other.
  std::map<std::string, uint32_t, std::less<>> ids;
  std::string_view group;
  ObjColours colours{name, notes, {}, {}, false, {}, {}, {}};
  bool has_colour = false, has_uv = false;  // a vertex colour or `vt` seen
  size_t number = 0;
  while (lines.next(line, number)) {
    text::split(line, '#', tokens);
    if (tokens.empty()) continue;
    if (tokens[0] == "v") {
      const glm::dvec3 p = text::parse_vertex(name, number, tokens);
      if (mesh.positions.size() >= (size_t(1) << 31))
        fail("{}: line {}: more vertices than voxr can index", name, number);
      if (tokens.size() == 7 || has_colour) {
        has_colour = true;
        colours.vertex_colour(mesh, number, tokens);
      }
      mesh.positions.push_back(p);
    } else if (tokens[0] == "f" || tokens[0] == "fo") {
      corners.clear();
      for (size_t k = 1; k < tokens.size(); ++k) {
        const std::string_view token = tokens[k];
        corners.push_back(resolve_index(name, number, token, token.substr(0, token.find('/')),
                                        mesh.positions.size(), "vertex", "vertices"));
      }
      mesh.add_face(corners.data(), uint32_t(corners.size()));
      if (has_uv) colours.corner_uvs(mesh, number, tokens);
      auto id = ids.find(group);
      if (id == ids.end()) id = ids.emplace(std::string(group), uint32_t(ids.size())).first;
      mesh.materials.push_back(id->second);
    } else if (tokens[0] == "vt") {
      has_uv = true;
      colours.texture_coordinate(number, tokens);
    } else if (tokens[0] == "usemtl") {
      group = rest_of(tokens, 1);  // the name is the rest of the statement (names may hold spaces)
    } else if (tokens[0] == "mtllib") {
      colours.material_libraries(number, tokens);
    }
  }
  colours.finish(mesh, ids);
  if (ids.size() <= 1) mesh.materials.clear();  // one material: every face has id 0
  return mesh;
}

}  // namespace voxr
