// ASCII OFF, read here: OpenMesh's OFF reader (9.0) takes neither comments nor counts on the keyword line,
// reads uninitialised memory on malformed numbers and keeps the binary flag of the previous file.
#include <algorithm>
#include <exception>
#include <thread>

#include <unordered_map>

#include "mesh/mesh_readers.h"
#include "mesh/texture_reader.h"
#include "util/text_scan.h"

namespace voxr {

namespace {

using text::is_space;
using text::printable;

// What an OFF body has promised and what has been read of it.
struct OffBody {
  // `bytes`: the size of the text to read. Headers can lie: reserve only what that text can hold (a vertex
  // line "0 0 0" takes 6 bytes, a face line "3 0 1 2" 8).
  OffBody(const std::string& file, size_t vertex_count, size_t vertex_lines, size_t face_lines, size_t bytes)
      : name(file), vertices(vertex_count), wanted(vertex_lines), faces(face_lines) {
    mesh.positions.reserve(std::min(wanted, bytes / 6));
    mesh.face_sizes.reserve(std::min(faces, bytes / 8));
    mesh.indices.reserve(3 * std::min(faces, bytes / 8));
  }
  const std::string& name;
  size_t vertices;  // in the file: face indices are checked against it
  size_t wanted;    // vertices to read here (all of them, or none when reading from the first face on)
  size_t faces;     // faces to read here
  // Vertex colour columns (COFF, CNOFF, STCOFF ...): where they start (after x y z and a normal), -1 when
  // the keyword has no C; how many numbers follow them (2 with ST).
  int colour_at = -1;
  size_t after_colour = 0;
  PolygonMesh mesh;
  std::unordered_map<uint32_t, uint32_t> look_of_colour;  // face colours -> looks
  size_t f() const { return mesh.face_sizes.size(); }
  bool done() const { return mesh.positions.size() == wanted && f() == faces; }

  uint32_t look(uint32_t rgba) {
    const auto [it, added] = look_of_colour.try_emplace(rgba, uint32_t(mesh.looks.size()));
    if (added) mesh.looks.push_back(SurfaceLook{rgba, -1});
    return it->second;
  }
  // Records the colour of the face just added: `rgba`, or none (white once any face has a colour).
  void face_colour(bool has, uint32_t rgba) {
    if (!has && mesh.face_looks.empty()) return;
    if (mesh.face_looks.empty() && f() > 1) mesh.face_looks.assign(f() - 1, look(kWhiteRgba));
    mesh.face_looks.push_back(look(has ? rgba : kWhiteRgba));
  }
};

// A colour of 3 or 4 components from tokens[first, first + count): integers 0..255 when every token is
// written as an integer, numbers in [0, 1] otherwise (OFF writers use both). Fails naming the line.
uint32_t off_colour(const std::string& name, size_t number, const std::vector<std::string_view>& tokens,
                    size_t first, size_t count, const char* what) {
  bool integers = true;
  for (size_t k = first; k < first + count; ++k)
    integers &= tokens[k].find_first_not_of("+-0123456789") == std::string_view::npos;
  uint32_t c[4] = {255, 255, 255, 255};
  for (size_t k = 0; k < count; ++k) {
    double v = 0.0;
    text::parse_number(tokens[first + k], v);  // checked by check_numbers
    if (integers ? !(v >= 0.0 && v <= 255.0) : !(v >= 0.0 && v <= 1.0))
      fail("{}: line {}: {} component '{}' is not in {}", name, number, what, printable(tokens[first + k]),
           integers ? "0..255 (integers)" : "[0, 1] (numbers with a point)");
    c[k] = integers ? uint32_t(v) : unit_to_byte(v);
  }
  return pack_rgba(c[0], c[1], c[2], c[3]);
}

// Every token of `line` (outside comments) must be a finite number. Returns the number of tokens.
size_t check_numbers(const std::string& name, std::string_view line, size_t number,
                     std::vector<std::string_view>& tokens) {
  text::split(line, '#', tokens);
  double unused;
  for (std::string_view t : tokens)
    if (!text::parse_number(t, unused))
      fail("{}: line {}: '{}' is not a finite number (of magnitude at most {:g})", name, number, printable(t),
           text::kMaxCoordinate);
  return tokens.size();
}

// Reads one line of an OFF body, token by token. This is the definition of what a body line may hold: a
// vertex is x y z and then optional normal, colour or texture numbers; a face is n i1 .. in and then an
// optional colour. The fast scanner below hands it every line that is not plainly well formed, so it also
// names every error.
void read_off_line(OffBody& b, std::string_view line, size_t number, std::vector<std::string_view>& tokens) {
  const std::string& name = b.name;
  if (check_numbers(name, line, number, tokens) == 0) return;
  PolygonMesh& mesh = b.mesh;
  if (mesh.positions.size() < b.wanted) {
    if (tokens.size() < 3)
      fail("{}: line {}: vertex {} needs three coordinates", name, number, mesh.positions.size());
    glm::dvec3 p;
    for (int c = 0; c < 3; ++c) text::parse_number(tokens[c], p[c]);  // checked above
    if (b.colour_at >= 0) {
      // A vertex without the colour columns is white (files that say COFF and give none are common).
      const size_t at = size_t(b.colour_at);
      const size_t count = tokens.size() > at + b.after_colour ? tokens.size() - at - b.after_colour : 0;
      if (count != 0 && count != 3 && count != 4)
        fail("{}: line {}: vertex {} has {} colour components after column {}; a colour has 3 or 4", name,
             number, mesh.positions.size(), count, at);
      mesh.vertex_rgba.push_back(count == 0 ? kWhiteRgba
                                            : off_colour(name, number, tokens, at, count, "vertex colour"));
    }
    mesh.positions.push_back(p);
    return;
  }
  uint32_t n = 0;
  if (!text::parse_uint(tokens[0], n))
    fail("{}: line {}: the face vertex count '{}' is not a non-negative integer", name, number,
         printable(tokens[0]));
  if (n >= tokens.size()) fail("{}: line {}: face {} lists fewer than {} vertices", name, number, b.f(), n);
  for (size_t k = 1; k <= n; ++k) {
    uint32_t index = 0;
    if (!text::parse_uint(tokens[k], index) || index >= b.vertices)
      fail("{}: line {}: face {} uses vertex '{}' but the file has {} vertices", name, number, b.f(),
           printable(tokens[k]), b.vertices);
    mesh.indices.push_back(index);
  }
  mesh.face_sizes.push_back(n);
  // A colour after the indices: 3 or 4 components (1 or 2 numbers, a colour-map index, are ignored).
  const size_t extra = tokens.size() - 1 - n;
  const bool coloured = extra == 3 || extra == 4;
  b.face_colour(coloured, coloured ? off_colour(name, number, tokens, n + 1, extra, "face colour") : 0);
}

// The fast path: reads well-formed lines straight from the bytes, with the same from_chars calls on the same
// token text as read_off_line (a number never extends over whitespace, '#' or '\n', so parsing up to the end
// of the buffer stops where the token ends). Each function returns where the line's tokens end (at '\n',
// '#' or `end`), or nullptr for anything else (then read_off_line decides).
bool ends_token(char c) {
  return is_space(c) || c == '\n' || c == '#';
}
bool ends_line(const char* p, const char* end) {
  return p == end || *p == '\n' || *p == '#';
}
const char* skip_spaces(const char* p, const char* end) {
  while (p != end && is_space(*p)) ++p;
  return p;
}

// A token read as text::parse_number reads it; nullptr when it is not a number voxr accepts.
const char* scan_number(const char* p, const char* end, double& out) {
  if (*p == '+' && p + 1 != end && !ends_token(p[1])) ++p;
  double value = 0.0;
  const auto [e, ec] = std::from_chars(p, end, value);
  if (ec != std::errc() || (e != end && !ends_token(*e)) || !(std::abs(value) <= text::kMaxCoordinate))
    return nullptr;
  out = value;
  return e;
}

// A token of decimal digits, as from_chars reads it (other tokens and values of ten digits or more go
// to from_chars in read_off_line). Such a token is also a number.
const char* scan_uint(const char* p, const char* end, uint32_t& out) {
  uint32_t value = 0;
  const char* const start = p;
  for (; p != end && p - start < 9 && uint8_t(*p - '0') < 10; ++p) value = value * 10 + uint32_t(*p - '0');
  if (p == start || (p != end && !ends_token(*p))) return nullptr;
  out = value;
  return p;
}

// Numbers up to the end of the line; the first three are kept.
const char* scan_numbers(const char* p, const char* end, double (&first)[3], size_t& count) {
  count = 0;
  while (!ends_line(p, end)) {
    double value;
    p = scan_number(p, end, value);
    if (!p) return nullptr;
    if (count < 3) first[count] = value;
    ++count;
    p = skip_spaces(p, end);
  }
  return p;
}

const char* scan_vertex(OffBody& b, const char* p, const char* end) {
  if (b.colour_at >= 0) return nullptr;  // coloured vertices are read token by token
  double v[3];
  size_t count;
  p = scan_numbers(p, end, v, count);
  if (!p || count < 3) return nullptr;
  b.mesh.positions.push_back(glm::dvec3(v[0], v[1], v[2]));
  return p;
}

// Leaves the indices it added when it fails; the caller removes them.
const char* scan_face(OffBody& b, const char* p, const char* end) {
  uint32_t n = 0;
  p = scan_uint(p, end, n);
  for (uint32_t k = 1; p && k <= n; ++k) {
    p = skip_spaces(p, end);
    uint32_t index = 0;
    if (ends_line(p, end) || !(p = scan_uint(p, end, index)) || index >= b.vertices) return nullptr;
    b.mesh.indices.push_back(index);
  }
  if (!p) return nullptr;
  double colour[3];
  size_t count;
  p = scan_numbers(skip_spaces(p, end), end, colour, count);
  if (!p || count >= 3) return nullptr;  // a face colour is read token by token
  b.mesh.face_sizes.push_back(n);
  if (!b.mesh.face_looks.empty()) b.face_colour(false, 0);  // white, once an earlier face had a colour
  return p;
}

// After the '\n' that ends the line `p` is on (p at '\n', '#', `end` or any byte of the line).
const char* next_line(const char* p, const char* end) {
  const void* eol = std::memchr(p, '\n', size_t(end - p));
  return eol ? static_cast<const char*>(eol) + 1 : end;
}

// The line that starts at `p`, without its '\n'.
std::string_view whole_line(const char* p, const char* end) {
  const char* eol = next_line(p, end);
  return std::string_view(p, size_t(eol - p) - (eol != p && eol[-1] == '\n'));
}

// Reads body lines from `p` until `b` has what it wants or the text ends; `number` is the number of the line
// before `p` and moves along. Returns where reading stopped.
const char* read_off_body(OffBody& b, const char* p, const char* end, size_t& number) {
  std::vector<std::string_view> tokens;
  while (p != end && !b.done()) {
    ++number;
    const char* q = skip_spaces(p, end);
    if (!ends_line(q, end)) {
      const size_t indices = b.mesh.indices.size();
      q = b.mesh.positions.size() < b.wanted ? scan_vertex(b, q, end) : scan_face(b, q, end);
      if (!q) {
        b.mesh.indices.resize(indices);
        const std::string_view line = whole_line(p, end);
        read_off_line(b, line, number, tokens);
        q = line.data() + line.size();
      }
    }
    p = next_line(q, end);
  }
  return p;
}

// After the body: the counts must have been met, and whatever follows the last face must be numbers too.
void check_off_end(const OffBody& b, const char* p, const char* end, size_t number) {
  if (b.mesh.positions.size() < b.wanted)
    fail("{}: the file declares {} vertices but ends after {}", b.name, b.vertices, b.mesh.positions.size());
  if (b.f() < b.faces) fail("{}: the file declares {} faces but ends after {}", b.name, b.faces, b.f());
  std::vector<std::string_view> tokens;
  for (; p != end; p = next_line(p, end)) {
    ++number;
    double unused[3];
    size_t count;
    if (const char* q = scan_numbers(skip_spaces(p, end), end, unused, count)) {
      p = q;
    } else {
      const std::string_view line = whole_line(p, end);
      check_numbers(b.name, line, number, tokens);
      p = line.data() + line.size();
    }
  }
}

// Where the line after the `count`th line with tokens starts, moving `number` along; nullptr when the text
// has fewer such lines.
const char* skip_lines_with_tokens(const char* p, const char* end, size_t count, size_t& number) {
  for (; count > 0 && p != end; ++number) {
    const char* q = skip_spaces(p, end);
    count -= !ends_line(q, end);
    p = next_line(q, end);
  }
  return count == 0 ? p : nullptr;
}

// One face colour for every face: one look and no per-face list (triangle_soup.h: look 0 for every
// triangle).
PolygonMesh finish(PolygonMesh mesh) {
  if (mesh.looks.size() == 1) mesh.face_looks.clear();
  return mesh;
}

}  // namespace

PolygonMesh read_off(const std::string& name, std::string_view bytes) {
  text::Lines lines(bytes);
  std::string_view line;
  std::vector<std::string_view> tokens, header;
  size_t number = 0;
  // Keyword ([ST][C][N]OFF), then "vertices faces edges", on the same line or the next ones.
  while (header.size() < 4 && lines.next(line, number)) {
    text::split(line, '#', tokens);
    for (size_t k = 0; k < tokens.size(); ++k) {
      const std::string_view t = tokens[k];
      if (header.empty()) {
        if (t.size() < 3 || t.substr(t.size() - 3) != "OFF")
          fail("{}: line {}: an OFF file starts with the keyword OFF, not '{}'", name, number, printable(t));
        if (t.find_first_of("n4") != std::string_view::npos)
          fail("{}: line {}: '{}' files are not supported, only 3D OFF", name, number, printable(t));
      }
      if (header.size() == 1 && t == "BINARY")
        fail("{}: line {}: binary OFF is not supported; convert the file to ASCII OFF or PLY", name, number);
      header.push_back(t);
      if (header.size() == 4) {
        if (k + 1 != tokens.size()) fail("{}: line {}: unexpected text after the OFF counts", name, number);
        break;
      }
    }
  }
  if (header.size() < 4) fail("{}: the OFF header ends before the vertex, face and edge counts", name);
  // Geomview's vertex columns: x y z, then nx ny nz (N), then a colour (C), then s t (ST).
  const std::string_view prefix = header[0].substr(0, header[0].size() - 3);
  const int colour_at = prefix.find('C') != std::string_view::npos
                            ? 3 + (prefix.find('N') != std::string_view::npos ? 3 : 0)
                            : -1;
  const size_t after_colour = prefix.find("ST") != std::string_view::npos ? 2 : 0;
  const size_t vertices = text::parse_count(name, number, header[1], "vertex");
  const size_t faces = text::parse_count(name, number, header[2], "face");
  text::parse_count(name, number, header[3], "edge");
  if (vertices >= (size_t(1) << 31) || faces >= (size_t(1) << 31))
    fail("{}: line {}: {} vertices and {} faces are more than voxr can index", name, number, vertices, faces);

  const std::string_view body = lines.rest();
  const char* const end = body.data() + body.size();
  // A large file is read by two threads, the vertices here and the faces (from the line after the last
  // vertex line) on another; an error in the vertices is reported first, as it comes first in the file.
  size_t face_number = number;
  const char* face_start = body.size() >= (size_t(1) << 20) && vertices > 0 && faces > 0
                               ? skip_lines_with_tokens(body.data(), end, vertices, face_number)
                               : nullptr;
  if (face_start) {
    OffBody v(name, vertices, vertices, 0, size_t(face_start - body.data())),
        f(name, vertices, 0, faces, size_t(end - face_start));
    v.colour_at = colour_at;
    v.after_colour = after_colour;
    std::exception_ptr face_error;
    std::thread face_reader([&] {
      try {
        const char* rest = read_off_body(f, face_start, end, face_number);
        check_off_end(f, rest, end, face_number);
      } catch (...) {
        face_error = std::current_exception();
      }
    });
    try {
      read_off_body(v, body.data(), face_start, number);
      check_off_end(v, face_start, face_start, number);
    } catch (...) {
      face_reader.join();
      throw;
    }
    face_reader.join();
    if (face_error) std::rethrow_exception(face_error);
    f.mesh.positions = std::move(v.mesh.positions);
    f.mesh.vertex_rgba = std::move(v.mesh.vertex_rgba);
    return finish(std::move(f.mesh));
  }
  OffBody b(name, vertices, vertices, faces, body.size());
  b.colour_at = colour_at;
  b.after_colour = after_colour;
  const char* rest = read_off_body(b, body.data(), end, number);
  check_off_end(b, rest, end, number);
  return finish(std::move(b.mesh));
}

}  // namespace voxr
