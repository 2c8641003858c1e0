// PLY 1.0 (Turk's polygon file format): a header of elements and their properties, then the elements in
// ASCII or binary of either byte order. Every property is read by its declared type, in declared order, so
// a face element may hold any properties before or after its index list; the vertex element gives x, y, z
// of any scalar type and the face element a list named vertex_indices (or vertex_index) of any integer type.
// Colour: red, green, blue and optional alpha on the vertex element (vertex colours) or the face element
// (face colours, one look per distinct colour), integers 0..255 or floats in [0, 1]. With MeshLab's
// `comment TextureFile NAME` (relative to the file): its texture for every face, sampled at texture
// coordinates per vertex (s t, u v, texture_u texture_v) or per face corner (a `texcoord` list of u v pairs;
// vertices whose corners differ are split).
#include <algorithm>
#include <cstring>
#include <filesystem>
#include <map>
#include <tuple>
#include <type_traits>
#include <unordered_map>

#include "mesh/mesh_readers.h"
#include "mesh/texture_reader.h"
#include "util/text_scan.h"

namespace voxr {

namespace {

using text::printable;

enum class PlyType { kI8, kU8, kI16, kU16, kI32, kU32, kF32, kF64, kUnknown };

PlyType ply_type(std::string_view name) {
  if (name == "char" || name == "int8") return PlyType::kI8;
  if (name == "uchar" || name == "uint8") return PlyType::kU8;
  if (name == "short" || name == "int16") return PlyType::kI16;
  if (name == "ushort" || name == "uint16") return PlyType::kU16;
  if (name == "int" || name == "int32") return PlyType::kI32;
  if (name == "uint" || name == "uint32") return PlyType::kU32;
  if (name == "float" || name == "float32") return PlyType::kF32;
  if (name == "double" || name == "float64") return PlyType::kF64;
  return PlyType::kUnknown;
}

size_t type_size(PlyType t) {
  constexpr size_t sizes[] = {1, 1, 2, 2, 4, 4, 4, 8, 0};
  return sizes[int(t)];
}
bool is_float(PlyType t) {
  return t == PlyType::kF32 || t == PlyType::kF64;
}

struct PlyProperty {
  std::string name;
  PlyType type = PlyType::kUnknown;        // of the scalar, or of each list item
  PlyType count_type = PlyType::kUnknown;  // lists: of the item count; kUnknown for scalars
  bool list() const { return count_type != PlyType::kUnknown; }
};

struct PlyElement {
  std::string name;
  size_t count = 0;
  std::vector<PlyProperty> properties;
};

enum class Format { kAscii, kLittle, kBig };

// Reads the values of the body one by one, ASCII or binary; every failure names the element, its index and
// the property being read.
class BodyReader {
 public:
  BodyReader(const std::string& name, std::string_view body, Format format, size_t first_line)
      : name_(name), p_(body.data()), end_(body.data() + body.size()), format_(format), line_(first_line) {}

  void at(const PlyElement& e, size_t index, const PlyProperty& p) {
    element_ = &e;
    index_ = index;
    property_ = &p;
  }

  // The next value, of type `t`, as a double (exact for every PLY integer type). NaN and infinity pass
  // here (a quality property may hold them); coordinates are checked with `finite`.
  double value(PlyType t) { return format_ == Format::kAscii ? ascii_value(t) : binary_value(t); }

  double finite(double v) const {
    if (!(std::abs(v) <= text::kMaxCoordinate)) fault(fmt::format("{} is not a finite coordinate", v));
    return v;
  }

  // The next value as a list length or index: an integer of type `t` that is not negative.
  uint64_t count(PlyType t) {
    const double v = value(t);
    if (v < 0) fault(fmt::format("negative value {}", v));
    return uint64_t(v);
  }

  // ASCII: an element's values end its line; more values there mean the header declares fewer properties
  // than the body holds, and reading on would shift every value after them.
  void end_row() {
    if (format_ != Format::kAscii) return;
    while (p_ != end_ && text::is_space(*p_)) ++p_;
    if (p_ != end_ && *p_ != '\n')
      fail("{}: line {}: {} {} of {} has more values than its {} properties", name_, line_, element_->name,
           index_, element_->count, element_->properties.size());
  }

  [[noreturn]] void fault(const std::string& what) const {
    const std::string where = format_ == Format::kAscii ? fmt::format("line {}: ", line_) : std::string();
    fail("{}: {}{} {} of {}, property '{}': {}", name_, where, element_->name, index_, element_->count,
         property_->name, what);
  }

 private:
  double ascii_value(PlyType t) {
    while (p_ != end_ && (text::is_space(*p_) || *p_ == '\n')) line_ += *p_++ == '\n';
    const char* start = p_;
    while (p_ != end_ && !text::is_space(*p_) && *p_ != '\n') ++p_;
    const std::string_view token(start, size_t(p_ - start));
    if (token.empty()) fault("the file ends here");
    if (is_float(t)) {
      const std::string_view digits = token.size() > 1 && token[0] == '+' ? token.substr(1) : token;
      double v = 0.0;
      const auto [e, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), v);
      if (ec != std::errc() || e != digits.data() + digits.size())
        fault(fmt::format("'{}' is not a number", printable(token)));
      return v;
    }
    long long v = 0;
    const auto [e, ec] = std::from_chars(token.data(), token.data() + token.size(), v);
    const bool is_unsigned = t == PlyType::kU8 || t == PlyType::kU16 || t == PlyType::kU32;
    const int bits = int(8 * type_size(t));
    const long long lo = is_unsigned ? 0 : -(1ll << (bits - 1));
    const long long hi = is_unsigned ? (1ll << bits) - 1 : (1ll << (bits - 1)) - 1;
    if (ec != std::errc() || e != token.data() + token.size() || v < lo || v > hi)
      fault(fmt::format("'{}' is not a value of the declared integer type", printable(token)));
    return double(v);
  }

  double binary_value(PlyType t) {
    const size_t n = type_size(t);
    if (size_t(end_ - p_) < n) fault("the file ends here");
    unsigned char b[8];
    std::memcpy(b, p_, n);
    p_ += n;
    if (format_ == Format::kBig) std::reverse(b, b + n);  // to little-endian, this machine's order
    switch (t) {
      case PlyType::kI8:
        return double(int8_t(b[0]));
      case PlyType::kU8:
        return double(b[0]);
      case PlyType::kI16:
        return double(load<int16_t>(b));
      case PlyType::kU16:
        return double(load<uint16_t>(b));
      case PlyType::kI32:
        return double(load<int32_t>(b));
      case PlyType::kU32:
        return double(load<uint32_t>(b));
      case PlyType::kF32:
        return double(load<float>(b));
      case PlyType::kF64:
        return load<double>(b);
      case PlyType::kUnknown:
        break;
    }
    fault("unknown type");
  }
  template <typename T>
  static T load(const unsigned char* b) {
    T v;
    std::memcpy(&v, b, sizeof v);
    return v;
  }
  const std::string& name_;
  const char* p_;
  const char* end_;
  Format format_;
  size_t line_;
  const PlyElement* element_ = nullptr;
  size_t index_ = 0;
  const PlyProperty* property_ = nullptr;
};

struct Header {
  Format format = Format::kAscii;
  std::vector<PlyElement> elements;
  size_t bytes = 0;  // up to and including the end_header line
  size_t lines = 0;
  std::string texture_file;  // `comment TextureFile NAME` (MeshLab's), relative to the PLY file
  size_t texture_line = 0;
};

Header read_header(const std::string& name, std::string_view bytes) {
  text::Lines lines(bytes);
  std::string_view line;
  std::vector<std::string_view> tokens;
  size_t number = 0;
  Header h;
  bool has_format = false, ended = false;
  while (!ended && lines.next(line, number)) {
    h.bytes += line.size() + 1;
    text::split(line, 0, tokens);
    if (number == 1 && (tokens.size() != 1 || tokens[0] != "ply"))
      fail("{}: line 1: a PLY file starts with the line 'ply'", name);
    if (tokens.size() >= 3 && tokens[0] == "comment" && tokens[1] == "TextureFile") {
      h.texture_file =
          std::string(tokens[2].data(), tokens.back().data() + tokens.back().size() - tokens[2].data());
      h.texture_line = number;
    }
    if (tokens.empty() || number == 1 || tokens[0] == "comment" || tokens[0] == "obj_info") continue;
    if (tokens[0] == "format") {
      if (tokens.size() < 2) fail("{}: line {}: a format line reads 'format TYPE 1.0'", name, number);
      if (tokens[1] == "ascii") {
        h.format = Format::kAscii;
      } else if (tokens[1] == "binary_little_endian") {
        h.format = Format::kLittle;
      } else if (tokens[1] == "binary_big_endian") {
        h.format = Format::kBig;
      } else {
        fail("{}: line {}: unknown PLY format '{}'", name, number, printable(tokens[1]));
      }
      has_format = true;
    } else if (tokens[0] == "element") {
      if (tokens.size() != 3) fail("{}: line {}: an element line reads 'element NAME COUNT'", name, number);
      h.elements.push_back(
          {std::string(tokens[1]), text::parse_count(name, number, tokens[2], "element"), {}});
    } else if (tokens[0] == "property") {
      if (h.elements.empty()) fail("{}: line {}: a property before any element", name, number);
      const bool list = tokens.size() == 5 && tokens[1] == "list";
      if (!list && tokens.size() != 3)
        fail(
            "{}: line {}: a property line reads 'property TYPE NAME' or 'property list COUNT_TYPE TYPE NAME'",
            name, number);
      PlyProperty p;
      p.name = std::string(tokens.back());
      p.type = ply_type(tokens[list ? 3 : 1]);
      if (p.type == PlyType::kUnknown)
        fail("{}: line {}: element '{}' property '{}' has unknown PLY type '{}'", name, number,
             h.elements.back().name, printable(p.name), printable(tokens[list ? 3 : 1]));
      if (list) {
        p.count_type = ply_type(tokens[2]);
        if (p.count_type == PlyType::kUnknown || is_float(p.count_type))
          fail("{}: line {}: element '{}' property '{}': a list count must have an integer type, not '{}'",
               name, number, h.elements.back().name, printable(p.name), printable(tokens[2]));
      }
      h.elements.back().properties.push_back(std::move(p));
    } else if (tokens[0] == "end_header") {
      ended = true;
    } else {
      fail("{}: line {}: unknown PLY header line '{}'", name, number, printable(tokens[0]));
    }
  }
  if (!ended) fail("{}: the PLY header has no end_header line", name);
  if (!has_format) fail("{}: the PLY header has no format line", name);
  h.lines = number;
  return h;
}

// A colour component as a byte: integer types hold 0..255, floating-point ones [0, 1].
uint32_t colour_byte(const BodyReader& r, PlyType t, double v) {
  if (is_float(t)) {
    if (!(v >= 0.0 && v <= 1.0)) r.fault(fmt::format("colour value {} is not in [0, 1]", v));
    return unit_to_byte(v);
  }
  if (v < 0.0 || v > 255.0) r.fault(fmt::format("colour value {} is not in 0..255", v));
  return uint32_t(v);
}

// Gives every vertex the texture coordinates of its corners (`corner_uv`, parallel to mesh.indices): a vertex
// whose corners carry different ones is split, its first corner's keeping the vertex and each other value a
// copy (position and colour) appended at the end.
void split_corner_uvs(const std::string& name, PolygonMesh& mesh, const std::vector<glm::vec2>& corner_uv) {
  const size_t original = mesh.positions.size();
  std::vector<bool> seen(original, false);
  mesh.vertex_uv.assign(original, glm::vec2(0.0f));
  std::map<std::tuple<uint32_t, float, float>, uint32_t> copies;
  for (size_t i = 0; i < mesh.indices.size(); ++i) {
    const uint32_t v = mesh.indices[i];
    const glm::vec2 uv = corner_uv[i] + glm::vec2(0.0f);  // -0 as +0
    if (!seen[v]) {
      seen[v] = true;
      mesh.vertex_uv[v] = uv;
      continue;
    }
    if (mesh.vertex_uv[v] == uv) continue;
    const auto [it, added] = copies.try_emplace({v, uv.x, uv.y}, uint32_t(mesh.positions.size()));
    if (added) {
      if (mesh.positions.size() >= (size_t(1) << 31))
        fail("{}: more vertices than voxr can index after splitting them at texture seams", name);
      mesh.positions.push_back(mesh.positions[v]);
      if (!mesh.vertex_rgba.empty()) mesh.vertex_rgba.push_back(mesh.vertex_rgba[v]);
      mesh.vertex_uv.push_back(uv);
    }
    mesh.indices[i] = it->second;
  }
}

// The colour and texture work of read_ply's element loop, out of line: inlined, it made GCC stop inlining the
// loop's own calls (6 % more instructions reading a binary PLY without colour).
[[gnu::noinline]] void read_texcoords(BodyReader& r, PlyType type, uint64_t n, std::vector<glm::vec2>& out) {
  if (n % 2 != 0 || n > (2u << 20)) r.fault(fmt::format("{} texture coordinates are not u v pairs", n));
  for (uint64_t j = 0; j < n; j += 2) {
    const float u = float(r.finite(r.value(type)));
    out.push_back(glm::vec2(u, float(r.finite(r.value(type)))));
  }
}

[[gnu::noinline]] void add_corner_uvs(const BodyReader& r, const std::vector<glm::vec2>& face_uv,
                                      uint64_t corners, std::vector<glm::vec2>& corner_uv) {
  if (face_uv.size() != corners)
    r.fault(fmt::format("{} texture coordinate pairs for {} corners", face_uv.size(), corners));
  corner_uv.insert(corner_uv.end(), face_uv.begin(), face_uv.end());
}

// A face colour's look, one per distinct colour in order of first use.
[[gnu::noinline]] void add_face_look(PolygonMesh& mesh,
                                     std::unordered_map<uint32_t, uint32_t>& look_of_colour, uint32_t rgba) {
  const auto [look, added] = look_of_colour.try_emplace(rgba, uint32_t(mesh.looks.size()));
  if (added) mesh.looks.push_back(SurfaceLook{rgba, -1});
  mesh.face_looks.push_back(look->second);
}

// Index of the property named `wanted` in `e`, or -1.
int find_property(const PlyElement& e, std::initializer_list<std::string_view> wanted) {
  for (size_t i = 0; i < e.properties.size(); ++i)
    for (std::string_view w : wanted)
      if (e.properties[i].name == w) return int(i);
  return -1;
}

}  // namespace

PolygonMesh read_ply(const std::string& name, std::string_view bytes) {
  const Header h = read_header(name, bytes);
  const auto vertex_element = std::find_if(h.elements.begin(), h.elements.end(),
                                           [](const PlyElement& e) { return e.name == "vertex"; });
  if (vertex_element == h.elements.end()) fail("{}: the PLY header declares no 'vertex' element", name);
  const size_t vertices = vertex_element->count;
  if (vertices >= (size_t(1) << 31)) fail("{}: {} vertices are more than voxr can index", name, vertices);
  int xyz[3];
  for (int c = 0; c < 3; ++c) {
    const char* axis[] = {"x", "y", "z"};
    xyz[c] = find_property(*vertex_element, {axis[c]});
    if (xyz[c] < 0) fail("{}: element 'vertex' has no property '{}'", name, axis[c]);
    if (vertex_element->properties[xyz[c]].list())
      fail("{}: element 'vertex' property '{}' is a list; a coordinate must be a scalar", name, axis[c]);
  }
  bool has_faces = false;
  for (const PlyElement& e : h.elements) {
    if (e.name != "face") continue;
    has_faces = true;
    const int k = find_property(e, {"vertex_indices", "vertex_index"});
    if (k < 0) fail("{}: element 'face' has no list property 'vertex_indices'", name);
    if (!e.properties[k].list())
      fail("{}: element 'face' property '{}' is a scalar; it must be a list of vertex indices", name,
           e.properties[k].name);
    if (is_float(e.properties[k].type))
      fail("{}: element 'face' property '{}' has a floating-point item type; vertex indices are integers",
           name, e.properties[k].name);
  }
  if (!has_faces) fail("{}: the PLY header declares no 'face' element", name);

  PolygonMesh mesh;
  const std::string_view body = bytes.substr(std::min(h.bytes, bytes.size()));
  // Headers can lie: reserve only what the body can hold (a vertex takes 3 bytes or more).
  mesh.positions.reserve(std::min(vertices, body.size() / 3));
  BodyReader r(name, body, h.format, h.lines + 1);
  std::vector<uint32_t> corners;
  // Face colours become looks, one per distinct colour in order of first use.
  std::unordered_map<uint32_t, uint32_t> look_of_colour;
  // With a TextureFile: texture coordinates per vertex (s t, u v, texture_u texture_v) or per face corner (a
  // face list `texcoord` of u v pairs, MeshLab's wedge coordinates).
  const bool textured = !h.texture_file.empty();
  std::vector<glm::vec2> corner_uv, face_uv;
  for (const PlyElement& e : h.elements) {
    // An element without properties takes no bytes, whatever count the header gives it (up to 2^64 - 1).
    if (e.properties.empty()) continue;
    const bool is_vertex = &e == &*vertex_element, is_face = e.name == "face";
    const int index_list = is_face ? find_property(e, {"vertex_indices", "vertex_index"}) : -1;
    // What each scalar property is: a coordinate (0..2), a colour component (3..6: red, green, blue,
    // alpha; only when red, green and blue are all there), or nothing (-1).
    std::vector<int> role(e.properties.size(), -1);
    if (is_vertex)
      for (int c = 0; c < 3; ++c) role[size_t(xyz[c])] = c;
    bool coloured = false;
    if (is_vertex || is_face) {
      const int rgba[4] = {
          find_property(e, {"red", "diffuse_red", "r"}), find_property(e, {"green", "diffuse_green", "g"}),
          find_property(e, {"blue", "diffuse_blue", "b"}), find_property(e, {"alpha", "diffuse_alpha", "a"})};
      coloured = rgba[0] >= 0 && rgba[1] >= 0 && rgba[2] >= 0;
      for (int c = 0; c < 4 && coloured; ++c)
        if (rgba[c] >= 0) {
          if (e.properties[size_t(rgba[c])].list())
            fail("{}: element '{}' property '{}' is a list; a colour component must be a scalar", name,
                 e.name, e.properties[size_t(rgba[c])].name);
          role[size_t(rgba[c])] = 3 + c;
        }
    }
    if (coloured && is_vertex) mesh.vertex_rgba.reserve(mesh.positions.capacity());
    bool vertex_uv = false;
    if (textured && is_vertex) {
      const int uv[2] = {find_property(e, {"s", "u", "texture_u", "texture_s"}),
                         find_property(e, {"t", "v", "texture_v", "texture_t"})};
      vertex_uv = uv[0] >= 0 && uv[1] >= 0 && !e.properties[size_t(uv[0])].list() &&
                  !e.properties[size_t(uv[1])].list();
      if (vertex_uv) role[size_t(uv[0])] = 7, role[size_t(uv[1])] = 8;
    }
    const int texcoord_list = textured && is_face ? find_property(e, {"texcoord", "texcoords"}) : -1;
    // The rows, in one of two instantiations: an element without colour or texture coordinates (the
    // common case) runs the loop it ran before colour was read, with none of the colour work in it.
    auto read_rows = [&](auto with_colour) {
      constexpr bool kColour = decltype(with_colour)::value;
      for (size_t i = 0; i < e.count; ++i) {
        glm::dvec3 p(0.0);
        [[maybe_unused]] uint32_t colour[4] = {255, 255, 255, 255};
        [[maybe_unused]] glm::vec2 uv(0.0f);
        [[maybe_unused]] uint64_t face_corners = 0;
        if constexpr (kColour) face_uv.clear();
        for (size_t k = 0; k < e.properties.size(); ++k) {
          const PlyProperty& prop = e.properties[k];
          r.at(e, i, prop);
          if (!prop.list()) {
            const double v = r.value(prop.type);
            const int what = role[k];
            if constexpr (kColour) {
              if (what >= 7) {
                uv[what - 7] = float(r.finite(v));
                continue;
              }
              if (what >= 3) {
                colour[what - 3] = colour_byte(r, prop.type, v);
                continue;
              }
            }
            if (what >= 0) p[what] = r.finite(v);
            continue;
          }
          const uint64_t n = r.count(prop.count_type);
          if constexpr (kColour) {
            if (int(k) == texcoord_list) {
              read_texcoords(r, prop.type, n, face_uv);
              continue;
            }
          }
          if (int(k) != index_list) {
            for (uint64_t j = 0; j < n; ++j) r.value(prop.type);
            continue;
          }
          if constexpr (kColour) face_corners = n;
          if (n > (1u << 20)) r.fault(fmt::format("a face of {} corners", n));
          corners.resize(n);
          for (uint64_t j = 0; j < n; ++j) {
            const uint64_t v = r.count(prop.type);
            if (v >= vertices)
              r.fault(fmt::format("vertex index {} but the file has {} vertices", v, vertices));
            corners[j] = uint32_t(v);
          }
          mesh.add_face(corners.data(), uint32_t(n));
        }
        r.end_row();
        if (is_vertex) mesh.positions.push_back(p);
        if constexpr (kColour) {
          if (texcoord_list >= 0) add_corner_uvs(r, face_uv, face_corners, corner_uv);
          if (is_vertex) {
            if (coloured) mesh.vertex_rgba.push_back(pack_rgba(colour[0], colour[1], colour[2], colour[3]));
            if (vertex_uv) mesh.vertex_uv.push_back(uv);
          } else if (is_face && coloured) {
            add_face_look(mesh, look_of_colour, pack_rgba(colour[0], colour[1], colour[2], colour[3]));
          }
        }
      }
    };
    if (coloured || vertex_uv || texcoord_list >= 0)
      read_rows(std::true_type());
    else
      read_rows(std::false_type());
  }
  // One face colour for every face: one look, no per-face list (triangle_soup.h: look 0 for every triangle).
  if (mesh.looks.size() == 1) mesh.face_looks.clear();
  if (textured) {
    mesh.textures.push_back(
        read_texture(std::filesystem::path(name).parent_path() / h.texture_file, name, h.texture_line));
    if (mesh.looks.empty()) mesh.looks.push_back(SurfaceLook());
    for (SurfaceLook& look : mesh.looks) look.texture = 0;
    if (!corner_uv.empty()) split_corner_uvs(name, mesh, corner_uv);
  }
  return mesh;
}

}  // namespace voxr
