#include "core/mesh_loader.h"

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/System/omstream.hh>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstring>
#include <exception>
#include <limits>
#include <mutex>
#include <optional>
#include <string_view>
#include <system_error>
#include <thread>
#include <vector>

#include "core/error.h"

namespace voxr {

namespace {

using OpenMesh::EdgeHandle;
using OpenMesh::FaceHandle;
using OpenMesh::HalfedgeHandle;
using OpenMesh::VertexHandle;

// An OpenMesh importer that writes straight into a TriangleSoup. OpenMesh's own ImporterT builds a half-edge
// mesh, which duplicates the vertices of every non-manifold face and drops faces that repeat a vertex; the
// voxelizer needs neither restriction, and keeping the file's indices keeps closed meshes closed.
// Everything but positions and faces (normals, colours, texture coordinates, status) is ignored.
class SoupImporter final : public OpenMesh::IO::BaseImporter {
 public:
  explicit SoupImporter(TriangleSoup& soup) : soup_(soup) {}

  size_t faces_read() const { return faces_read_; }
  // First face that named a vertex the file does not have: {face, index}; face == SIZE_MAX when none.
  std::pair<size_t, int> bad_index() const { return bad_index_; }

  VertexHandle add_vertex(const OpenMesh::Vec3f& p) override {
    soup_.positions.push_back(glm::vec4(p[0], p[1], p[2], 1.0f));
    return VertexHandle(int(soup_.positions.size() - 1));
  }
  VertexHandle add_vertex(const OpenMesh::Vec3d& p) override {
    return add_vertex(OpenMesh::Vec3f(float(p[0]), float(p[1]), float(p[2])));
  }
  VertexHandle add_vertex() override { return add_vertex(OpenMesh::Vec3f(0.0f, 0.0f, 0.0f)); }
  void set_point(VertexHandle v, const OpenMesh::Vec3f& p) override {
    if (v.is_valid() && size_t(v.idx()) < soup_.positions.size())
      soup_.positions[v.idx()] = glm::vec4(p[0], p[1], p[2], 1.0f);
  }

  FaceHandle add_face(const VHandles& vs) override {
    const size_t face = faces_read_++;
    if (vs.size() < 3) return FaceHandle();
    for (const VertexHandle& v : vs)
      if (!v.is_valid() || size_t(v.idx()) >= soup_.positions.size()) {
        if (bad_index_.first == SIZE_MAX) bad_index_ = {face, v.idx()};
        return FaceHandle();
      }
    for (size_t k = 1; k + 1 < vs.size(); ++k)
      soup_.triangles.push_back(
          glm::uvec4(uint32_t(vs[0].idx()), uint32_t(vs[k].idx()), uint32_t(vs[k + 1].idx()), 0u));
    return FaceHandle(int(face));
  }
  FaceHandle add_face(HalfedgeHandle) override { return FaceHandle(); }
  HalfedgeHandle add_edge(VertexHandle, VertexHandle) override { return HalfedgeHandle(); }

  void reserve(unsigned int n_vertices, unsigned int, unsigned int n_faces) override {
    // Headers can lie; cap what a bad header can make us allocate up front.
    soup_.positions.reserve(std::min(n_vertices, 1u << 24));
    soup_.triangles.reserve(std::min(n_faces, 1u << 24));
  }
  size_t n_vertices() const override { return soup_.positions.size(); }
  size_t n_faces() const override { return faces_read_; }
  size_t n_edges() const override { return 0; }

  // Attributes voxr does not use.
  void add_face_texcoords(FaceHandle, VertexHandle, const std::vector<OpenMesh::Vec2f>&) override {}
  void add_face_texcoords(FaceHandle, VertexHandle, const std::vector<OpenMesh::Vec3f>&) override {}
  void set_face_texindex(FaceHandle, int) override {}
  void set_halfedge(VertexHandle, HalfedgeHandle) override {}
  void set_normal(VertexHandle, const OpenMesh::Vec3f&) override {}
  void set_normal(VertexHandle, const OpenMesh::Vec3d&) override {}
  void set_color(VertexHandle, const OpenMesh::Vec3uc&) override {}
  void set_color(VertexHandle, const OpenMesh::Vec4uc&) override {}
  void set_color(VertexHandle, const OpenMesh::Vec3f&) override {}
  void set_color(VertexHandle, const OpenMesh::Vec4f&) override {}
  void set_texcoord(VertexHandle, const OpenMesh::Vec2f&) override {}
  void set_status(VertexHandle, const OpenMesh::Attributes::StatusInfo&) override {}
  void set_next(HalfedgeHandle, HalfedgeHandle) override {}
  void set_face(HalfedgeHandle, FaceHandle) override {}
  void request_face_texcoords2D() override {}
  void set_texcoord(HalfedgeHandle, const OpenMesh::Vec2f&) override {}
  void set_texcoord(VertexHandle, const OpenMesh::Vec3f&) override {}
  void set_texcoord(HalfedgeHandle, const OpenMesh::Vec3f&) override {}
  void set_status(HalfedgeHandle, const OpenMesh::Attributes::StatusInfo&) override {}
  void set_color(EdgeHandle, const OpenMesh::Vec3uc&) override {}
  void set_color(EdgeHandle, const OpenMesh::Vec4uc&) override {}
  void set_color(EdgeHandle, const OpenMesh::Vec3f&) override {}
  void set_color(EdgeHandle, const OpenMesh::Vec4f&) override {}
  void set_status(EdgeHandle, const OpenMesh::Attributes::StatusInfo&) override {}
  void set_normal(FaceHandle, const OpenMesh::Vec3f&) override {}
  void set_normal(FaceHandle, const OpenMesh::Vec3d&) override {}
  void set_color(FaceHandle, const OpenMesh::Vec3uc&) override {}
  void set_color(FaceHandle, const OpenMesh::Vec4uc&) override {}
  void set_color(FaceHandle, const OpenMesh::Vec3f&) override {}
  void set_color(FaceHandle, const OpenMesh::Vec4f&) override {}
  void set_status(FaceHandle, const OpenMesh::Attributes::StatusInfo&) override {}
  void add_texture_information(int, std::string) override {}

 private:
  TriangleSoup& soup_;
  size_t faces_read_ = 0;
  std::pair<size_t, int> bad_index_{SIZE_MAX, 0};
};

// While alive, OpenMesh's diagnostic streams (omerr, omlog, omout) print nothing. The streams are global,
// so the caller holds a lock. (Redirecting them into a string would need mostream::connect/disconnect,
// and OpenMesh 9's disconnect leaks the target wrapper on every call.)
class SilenceOpenMesh {
 public:
  SilenceOpenMesh() {
    for (Stream& s : streams_) {
      s.was_enabled = s.stream.is_enabled();
      s.stream.disable();
    }
  }
  ~SilenceOpenMesh() {
    for (Stream& s : streams_) {
      s.stream.flush();  // drops a partial line, which the next enabled write would otherwise print
      if (s.was_enabled) s.stream.enable();
    }
  }
  SilenceOpenMesh(const SilenceOpenMesh&) = delete;
  SilenceOpenMesh& operator=(const SilenceOpenMesh&) = delete;

 private:
  struct Stream {
    OpenMesh::mostream& stream;
    bool was_enabled = true;
  };
  Stream streams_[3] = {{omerr()}, {omlog()}, {omout()}};
};

// ---------------------------------------------------------------------------------------------------------
// Pre-checks. OpenMesh's ASCII readers use stream extraction and do not check it: a vertex line that does
// not parse ("nan", "1.0x", a truncated file) is silently dropped (OBJ), read as zero (PLY, STL) or read
// as uninitialised memory (OFF); its binary readers read past the end of a truncated file. So before
// OpenMesh reads a file, every number the geometry depends on and the file's structure are checked here,
// and the counts a header promises are returned to be compared afterwards.

struct Expected {
  std::optional<size_t> vertices;
  std::optional<size_t> faces;
  // Set when the file was read here in full (ASCII OFF): OpenMesh is not needed.
  std::optional<TriangleSoup> parsed;
};

class Lines {
 public:
  explicit Lines(std::string_view text) : rest_(text) {}
  // The text after the last line returned (empty after the last line).
  std::string_view rest() const { return done_ ? std::string_view() : rest_; }
  // Next line with its 1-based number; false at the end.
  bool next(std::string_view& line, size_t& number) {
    if (done_) return false;
    const size_t eol = rest_.find('\n');
    line = rest_.substr(0, eol);
    if (eol == std::string_view::npos) {
      done_ = true;
    } else {
      rest_.remove_prefix(eol + 1);
    }
    number = ++line_;
    return true;
  }

 private:
  std::string_view rest_;
  size_t line_ = 0;
  bool done_ = false;
};

bool is_space(char c) {
  return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f';
}

// Splits `line` at whitespace, dropping everything from `comment` on (when comment != 0).
void split(std::string_view line, char comment, std::vector<std::string_view>& tokens) {
  tokens.clear();
  if (comment != 0) line = line.substr(0, line.find(comment));
  size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && is_space(line[i])) ++i;
    const size_t start = i;
    while (i < line.size() && !is_space(line[i])) ++i;
    if (i > start) tokens.push_back(line.substr(start, i - start));
  }
}

// `token` as it may be quoted in a message: at most 24 characters, bytes that are not printable ASCII as '?'.
std::string printable(std::string_view token) {
  std::string s(token.substr(0, 24));
  for (char& c : s)
    if (c < 0x20 || c > 0x7e) c = '?';
  return token.size() > 24 ? s + "..." : s;
}

// Parses a whole token as a number that is finite as a float (the soup's precision); false otherwise.
bool parse_float(std::string_view token, float& out) {
  if (token.size() > 1 && token[0] == '+') token.remove_prefix(1);
  double value = 0.0;
  const auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), value);
  if (ec != std::errc() || end != token.data() + token.size() || !std::isfinite(float(value))) return false;
  out = float(value);
  return true;
}

bool finite_number(std::string_view token) {
  float unused;
  return parse_float(token, unused);
}

// A vertex line "<keyword> x y z ...": the three coordinates must be finite numbers.
void check_coordinates(const std::string& name, size_t line, const std::vector<std::string_view>& tokens) {
  if (tokens.size() < 4) fail("{}: line {}: a vertex needs three coordinates", name, line);
  for (size_t k = 1; k <= 3; ++k)
    if (!finite_number(tokens[k]))
      fail("{}: line {}: vertex coordinate '{}' is not a finite number", name, line, printable(tokens[k]));
}

Expected check_obj(const std::string& name, std::string_view text) {
  Lines lines(text);
  std::string_view line;
  std::vector<std::string_view> tokens;
  size_t number = 0, vertices = 0;
  while (lines.next(line, number)) {
    split(line, '#', tokens);
    if (!tokens.empty() && tokens[0] == "v") {
      check_coordinates(name, number, tokens);
      ++vertices;
    }
  }
  Expected expected;
  expected.vertices = vertices;
  return expected;
}

Expected check_stl(const std::string& name, std::string_view text) {
  // Binary STL: an 80-byte header, a triangle count and 50 bytes per triangle.
  if (text.size() >= 84) {
    uint32_t n = 0;
    std::memcpy(&n, text.data() + 80, 4);
    if (84 + 50 * uint64_t(n) == text.size()) {
      // Per triangle: normal (3 floats), 3 corners (9 floats), 2 attribute bytes.
      for (uint32_t t = 0; t < n; ++t) {
        float corners[9];
        std::memcpy(corners, text.data() + 84 + 50 * size_t(t) + 12, sizeof corners);
        for (float c : corners)
          if (!std::isfinite(c))
            fail("{}: triangle {} has a vertex coordinate that is not finite ({})", name, t, c);
      }
      return {};
    }
  }
  Lines lines(text);
  std::string_view line;
  std::vector<std::string_view> tokens;
  size_t number = 0;
  while (lines.next(line, number)) {
    split(line, 0, tokens);
    if (!tokens.empty() && tokens[0] == "vertex") check_coordinates(name, number, tokens);
  }
  return {};
}

// Every token of `line` (outside comments) must be a finite number. Returns the number of tokens.
size_t check_numbers(const std::string& name, std::string_view line, size_t number, char comment,
                     std::vector<std::string_view>& tokens) {
  split(line, comment, tokens);
  for (std::string_view t : tokens)
    if (!finite_number(t)) fail("{}: line {}: '{}' is not a finite number", name, number, printable(t));
  return tokens.size();
}

// Every remaining token (outside comments) must be a finite number. Returns the number of non-empty lines.
size_t check_all_numbers(const std::string& name, Lines& lines, char comment) {
  std::string_view line;
  std::vector<std::string_view> tokens;
  size_t number = 0, rows = 0;
  while (lines.next(line, number)) rows += check_numbers(name, line, number, comment, tokens) > 0;
  return rows;
}

size_t parse_count(const std::string& name, size_t line, std::string_view token, const char* what) {
  size_t value = 0;
  const auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), value);
  if (ec != std::errc() || end != token.data() + token.size())
    fail("{}: line {}: the {} count '{}' is not a non-negative integer", name, line, what, printable(token));
  return value;
}

// What an OFF body has promised and what has been read of it.
struct OffBody {
  OffBody(const std::string& file, size_t vertex_count, size_t vertex_lines, size_t face_lines)
      : name(file), vertices(vertex_count), wanted(vertex_lines), faces(face_lines) {
    soup.positions.reserve(std::min(wanted, size_t(1) << 24));  // headers can lie: cap what they reserve
    soup.triangles.reserve(std::min(faces, size_t(1) << 24));
  }
  const std::string& name;
  size_t vertices;  // in the file: face indices are checked against it
  size_t wanted;    // vertices to read here (all of them, or none when reading from the first face on)
  size_t faces;     // faces to read here
  TriangleSoup soup;
  size_t f = 0;  // faces read
  bool done() const { return soup.positions.size() == wanted && f == faces; }
};

// Reads one line of an OFF body, token by token. This is the definition of what a body line may hold; the
// fast scanner below hands it every line that is not plainly well formed, so it also names every error.
void read_off_line(OffBody& b, std::string_view line, size_t number, std::vector<std::string_view>& tokens) {
  const std::string& name = b.name;
  if (check_numbers(name, line, number, '#', tokens) == 0) return;
  TriangleSoup& soup = b.soup;
  if (soup.positions.size() < b.wanted) {
    if (tokens.size() < 3)
      fail("{}: line {}: vertex {} needs three coordinates", name, number, soup.positions.size());
    glm::vec4 p(0.0f, 0.0f, 0.0f, 1.0f);
    for (int c = 0; c < 3; ++c) parse_float(tokens[c], p[c]);  // checked above
    soup.positions.push_back(p);
    return;
  }
  const size_t n = parse_count(name, number, tokens[0], "face vertex");
  if (n >= tokens.size()) fail("{}: line {}: face {} lists fewer than {} vertices", name, number, b.f, n);
  uint32_t first = 0, previous = 0;
  for (size_t k = 1; k <= n; ++k) {
    uint32_t index = 0;
    const auto [end, ec] = std::from_chars(tokens[k].data(), tokens[k].data() + tokens[k].size(), index);
    if (ec != std::errc() || end != tokens[k].data() + tokens[k].size() || index >= b.vertices)
      fail("{}: line {}: face {} uses vertex '{}' but the file has {} vertices", name, number, b.f,
           printable(tokens[k]), b.vertices);
    if (k == 1) first = index;
    if (k >= 3) soup.triangles.push_back(glm::uvec4(first, previous, index, 0u));
    previous = index;
  }
  ++b.f;
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

// A token read as parse_float reads it; nullptr when it is not a finite float.
const char* scan_float(const char* p, const char* end, float& out) {
  if (*p == '+' && p + 1 != end && !ends_token(p[1])) ++p;
  double value = 0.0;
  const auto [e, ec] = std::from_chars(p, end, value);
  if (ec != std::errc() || (e != end && !ends_token(*e)) || !std::isfinite(float(value))) return nullptr;
  out = float(value);
  return e;
}

// A token of decimal digits, as from_chars reads it (other tokens and values of ten digits or more go
// to from_chars in read_off_line). Such a token is also a finite float.
template <typename T>
const char* scan_uint(const char* p, const char* end, T& out) {
  static_assert(std::numeric_limits<T>::digits >= 32);
  uint32_t value = 0;
  const char* const start = p;
  for (; p != end && p - start < 9 && uint8_t(*p - '0') < 10; ++p) value = value * 10 + uint32_t(*p - '0');
  if (p == start || (p != end && !ends_token(*p))) return nullptr;
  out = T(value);
  return p;
}

// Finite numbers up to the end of the line; the first three are kept.
const char* scan_numbers(const char* p, const char* end, float (&first)[3], size_t& count) {
  count = 0;
  while (!ends_line(p, end)) {
    float value;
    p = scan_float(p, end, value);
    if (!p) return nullptr;
    if (count < 3) first[count] = value;
    ++count;
    p = skip_spaces(p, end);
  }
  return p;
}

const char* scan_vertex(OffBody& b, const char* p, const char* end) {
  float v[3];
  size_t count;
  p = scan_numbers(p, end, v, count);
  if (!p || count < 3) return nullptr;
  b.soup.positions.push_back(glm::vec4(v[0], v[1], v[2], 1.0f));
  return p;
}

// Leaves the triangles it added when it fails; the caller removes them.
const char* scan_face(OffBody& b, const char* p, const char* end) {
  size_t n = 0;
  p = scan_uint(p, end, n);
  uint32_t first = 0, previous = 0;
  for (size_t k = 1; p && k <= n; ++k) {
    p = skip_spaces(p, end);
    uint32_t index = 0;
    if (ends_line(p, end) || !(p = scan_uint(p, end, index)) || index >= b.vertices) return nullptr;
    if (k == 1) first = index;
    if (k >= 3) b.soup.triangles.push_back(glm::uvec4(first, previous, index, 0u));
    previous = index;
  }
  if (!p) return nullptr;
  float colour[3];
  size_t count;
  p = scan_numbers(skip_spaces(p, end), end, colour, count);
  if (p) ++b.f;
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
      const size_t triangles = b.soup.triangles.size();
      q = b.soup.positions.size() < b.wanted ? scan_vertex(b, q, end) : scan_face(b, q, end);
      if (!q) {
        b.soup.triangles.resize(triangles);
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
  if (b.soup.positions.size() < b.wanted)
    fail("{}: the file declares {} vertices but ends after {}", b.name, b.vertices, b.soup.positions.size());
  if (b.f < b.faces) fail("{}: the file declares {} faces but ends after {}", b.name, b.faces, b.f);
  std::vector<std::string_view> tokens;
  for (; p != end; p = next_line(p, end)) {
    ++number;
    float unused[3];
    size_t count;
    if (const char* q = scan_numbers(skip_spaces(p, end), end, unused, count)) {
      p = q;
    } else {
      const std::string_view line = whole_line(p, end);
      check_numbers(b.name, line, number, '#', tokens);
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

// ASCII OFF is read here rather than by OpenMesh, whose OFF reader (9.0) takes neither comments nor counts
// on the keyword line, reads uninitialised memory on malformed numbers and, reading from a stream, keeps
// the binary flag of the previous file. The checks below parse the whole file anyway.
Expected read_off(const std::string& name, std::string_view text) {
  Lines lines(text);
  std::string_view line;
  std::vector<std::string_view> tokens, header;
  size_t number = 0;
  // Keyword ([ST][C][N]OFF), then "vertices faces edges", on the same line or the next ones.
  while (header.size() < 4 && lines.next(line, number)) {
    split(line, '#', tokens);
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
  const size_t vertices = parse_count(name, number, header[1], "vertex");
  const size_t faces = parse_count(name, number, header[2], "face");
  parse_count(name, number, header[3], "edge");
  if (vertices >= (size_t(1) << 31) || faces >= (size_t(1) << 31))
    fail("{}: line {}: {} vertices and {} faces are more than voxr can index", name, number, vertices, faces);

  // One vertex per line (x y z, then optional normal/colour/texture numbers), then one face per line
  // (n i1 .. in, then an optional colour). Polygons are fanned from their first vertex.
  const std::string_view body = lines.rest();
  const char* const end = body.data() + body.size();
  TriangleSoup soup;
  // A large file is read by two threads, the vertices here and the faces (from the line after the last
  // vertex line) on another; an error in the vertices is reported first, as it comes first in the file.
  size_t face_number = number;
  const char* face_start = body.size() >= (size_t(1) << 20) && vertices > 0 && faces > 0
                               ? skip_lines_with_tokens(body.data(), end, vertices, face_number)
                               : nullptr;
  if (face_start) {
    OffBody v(name, vertices, vertices, 0), f(name, vertices, 0, faces);
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
    soup.positions = std::move(v.soup.positions);
    soup.triangles = std::move(f.soup.triangles);
  } else {
    OffBody b(name, vertices, vertices, faces);
    const char* rest = read_off_body(b, body.data(), end, number);
    check_off_end(b, rest, end, number);
    soup = std::move(b.soup);
  }
  if (soup.triangles.empty()) fail("{}: no triangles: the file has no face with 3 or more vertices", name);
  Expected result;
  result.parsed = std::move(soup);
  return result;
}

struct PlyProperty {
  std::string name;
  int size = 0;  // bytes of a scalar, or of each list item
  bool floating = false;
  int count_size = 0;  // lists: bytes of the item count; 0 for scalars
};

struct PlyElement {
  std::string name;
  size_t count = 0;
  std::vector<PlyProperty> properties;
};

// Size in bytes and float-ness of a PLY scalar type name; size 0 when unknown.
std::pair<int, bool> ply_type(std::string_view type) {
  if (type == "char" || type == "uchar" || type == "int8" || type == "uint8") return {1, false};
  if (type == "short" || type == "ushort" || type == "int16" || type == "uint16") return {2, false};
  if (type == "int" || type == "uint" || type == "int32" || type == "uint32") return {4, false};
  if (type == "float" || type == "float32") return {4, true};
  if (type == "double" || type == "float64") return {8, true};
  return {0, false};
}

// Reads an unsigned integer or a float of `size` bytes at `p` in the file's byte order.
uint64_t ply_uint(const char* p, int size, bool big_endian) {
  uint64_t v = 0;
  for (int i = 0; i < size; ++i)
    v |= uint64_t(uint8_t(p[big_endian ? i : size - 1 - i])) << (8 * (size - 1 - i));
  return v;
}

double ply_float(const char* p, int size, bool big_endian) {
  const uint64_t bits = ply_uint(p, size, big_endian);
  if (size == 4) {
    float f;
    const uint32_t b = uint32_t(bits);
    std::memcpy(&f, &b, 4);
    return f;
  }
  double d;
  std::memcpy(&d, &bits, 8);
  return d;
}

// Walks a binary PLY body so that OpenMesh never reads past the end, and checks vertex coordinates.
void check_ply_binary(const std::string& name, std::string_view body, const std::vector<PlyElement>& elements,
                      bool big_endian) {
  size_t at = 0;
  for (const PlyElement& e : elements) {
    size_t row_min = 0;
    for (const PlyProperty& p : e.properties) row_min += p.count_size ? p.count_size : p.size;
    if (row_min > 0 && e.count > (body.size() - at) / row_min)
      fail("{}: the header declares {} {} elements but the file is too short for them", name, e.count,
           e.name);
    for (size_t i = 0; i < e.count; ++i)
      for (const PlyProperty& p : e.properties) {
        size_t bytes = p.size;
        if (p.count_size) {
          if (body.size() - at < size_t(p.count_size))
            fail("{}: the file ends inside {} {} of {}", name, e.name, i, e.count);
          bytes = ply_uint(body.data() + at, p.count_size, big_endian) * p.size;
          at += p.count_size;
        }
        if (body.size() - at < bytes) fail("{}: the file ends inside {} {} of {}", name, e.name, i, e.count);
        if (e.name == "vertex" && !p.count_size && p.floating &&
            (p.name == "x" || p.name == "y" || p.name == "z")) {
          const double v = ply_float(body.data() + at, p.size, big_endian);
          if (!std::isfinite(float(v)))
            fail("{}: vertex {} has coordinate {} = {}, which is not a finite float", name, i, p.name, v);
        }
        at += bytes;
      }
  }
}

Expected check_ply(const std::string& name, std::string_view text) {
  Lines lines(text);
  std::string_view line;
  std::vector<std::string_view> tokens;
  size_t number = 0;
  std::vector<PlyElement> elements;
  std::string format;
  bool ended = false;
  size_t header_bytes = 0;
  while (!ended && lines.next(line, number)) {
    header_bytes += line.size() + 1;
    split(line, 0, tokens);
    if (number == 1 && (tokens.size() != 1 || tokens[0] != "ply"))
      fail("{}: line 1: a PLY file starts with the line 'ply'", name);
    if (tokens.empty()) continue;
    if (tokens[0] == "format") {
      if (tokens.size() < 2 ||
          (tokens[1] != "ascii" && tokens[1] != "binary_little_endian" && tokens[1] != "binary_big_endian"))
        fail("{}: line {}: unknown PLY format", name, number);
      format = tokens[1];
    } else if (tokens[0] == "element") {
      if (tokens.size() != 3) fail("{}: line {}: an element line reads 'element NAME COUNT'", name, number);
      elements.push_back({std::string(tokens[1]), parse_count(name, number, tokens[2], "element"), {}});
    } else if (tokens[0] == "property") {
      if (elements.empty()) fail("{}: line {}: a property before any element", name, number);
      PlyProperty p;
      const bool list = tokens.size() == 5 && tokens[1] == "list";
      if (!list && tokens.size() != 3)
        fail("{}: line {}: a property line reads 'property TYPE NAME'", name, number);
      const auto [size, floating] = ply_type(tokens[list ? 3 : 1]);
      if (size == 0)
        fail("{}: line {}: unknown PLY type '{}'", name, number, printable(tokens[list ? 3 : 1]));
      p.size = size;
      p.floating = floating;
      if (list) {
        const auto [count_size, count_floating] = ply_type(tokens[2]);
        if (count_size == 0 || count_floating)
          fail("{}: line {}: a list count must have an integer type, not '{}'", name, number,
               printable(tokens[2]));
        p.count_size = count_size;
      }
      p.name = std::string(tokens.back());
      elements.back().properties.push_back(std::move(p));
    }
    ended = tokens[0] == "end_header";
  }
  if (!ended) fail("{}: the PLY header has no end_header line", name);
  if (format.empty()) fail("{}: the PLY header has no format line", name);
  Expected expected;
  size_t total = 0;
  for (const PlyElement& e : elements) {
    total += e.count;
    if (e.name == "vertex") expected.vertices = e.count;
    if (e.name == "face") expected.faces = e.count;
  }
  if (format == "ascii") {
    // An ASCII body holds one element per line; fewer lines than elements means a truncated file.
    const size_t rows = check_all_numbers(name, lines, 0);
    if (rows < total)
      fail("{}: the header declares {} elements but the file ends after {}", name, total, rows);
  } else {
    check_ply_binary(name, text.substr(std::min(header_bytes, text.size())), elements,
                     format == "binary_big_endian");
  }
  return expected;
}

Expected check_text(const std::string& name, const std::string& ext, std::string_view text) {
  if (ext == ".obj") return check_obj(name, text);
  if (ext == ".off") return read_off(name, text);
  if (ext == ".ply") return check_ply(name, text);
  return check_stl(name, text);
}

// A file's bytes: mapped when it is a regular file, read otherwise. Mapping copies nothing and needs no fresh
// pages; reading a 40 MB mesh into a new buffer took longer than parsing it.
class FileBytes {
 public:
  explicit FileBytes(const std::filesystem::path& file) {
    const int fd = ::open(file.c_str(), O_RDONLY | O_CLOEXEC);
    if (fd < 0) fail("{}: cannot open the file for reading", file.string());
    struct stat st {};
    if (::fstat(fd, &st) == 0 && S_ISREG(st.st_mode) && st.st_size > 0) {
      void* map = ::mmap(nullptr, size_t(st.st_size), PROT_READ, MAP_PRIVATE, fd, 0);
      if (map != MAP_FAILED) {
        map_ = map;
        size_ = size_t(st.st_size);
      }
    }
    bool failed = false;
    if (!map_) {
      char chunk[1 << 16];
      for (;;) {
        const ssize_t n = ::read(fd, chunk, sizeof chunk);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) {
          failed = n < 0;
          break;
        }
        copy_.append(chunk, size_t(n));
      }
    }
    ::close(fd);
    if (failed) fail("{}: reading the file failed", file.string());
  }
  ~FileBytes() {
    if (map_) ::munmap(map_, size_);
  }
  FileBytes(const FileBytes&) = delete;
  FileBytes& operator=(const FileBytes&) = delete;

  std::string_view view() const {
    return map_ ? std::string_view(static_cast<const char*>(map_), size_) : copy_;
  }

 private:
  void* map_ = nullptr;
  size_t size_ = 0;
  std::string copy_;
};

std::string lower_extension(const std::filesystem::path& file) {
  std::string ext = file.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return ext;
}

std::string supported_list() {
  std::string s;
  for (const char* e : kMeshExtensions) s += (s.empty() ? "" : ", ") + std::string(e);
  return s;
}

std::mutex& openmesh_mutex() {
  static std::mutex m;
  return m;
}

}  // namespace

bool is_mesh_file(const std::filesystem::path& file) {
  const std::string ext = lower_extension(file);
  return std::any_of(std::begin(kMeshExtensions), std::end(kMeshExtensions),
                     [&](const char* e) { return ext == e; });
}

TriangleSoup load_mesh(const std::filesystem::path& file) {
  const std::string name = file.string();
  if (!is_mesh_file(file))
    fail("{}: unsupported mesh format '{}' (supported: {})", name, file.extension().string(),
         supported_list());

  std::error_code ec;
  const auto status = std::filesystem::status(file, ec);
  if (!std::filesystem::exists(status)) fail("{}: no such file", name);
  if (std::filesystem::is_directory(status)) fail("{}: is a directory, not a mesh file", name);
  const std::string ext = lower_extension(file);
  Expected expected;
  {
    const FileBytes data(file);
    if (data.view().empty()) fail("{}: the file is empty", name);
    expected = check_text(name, ext, data.view());
  }

  // read_off has checked what validate_soup would (faces, indices below the vertex count, finite
  // coordinates); on a large mesh the check cost more than a tenth of the load.
  if (expected.parsed) return std::move(*expected.parsed);

  TriangleSoup soup;
  SoupImporter importer(soup);
  bool ok = false;
  {
    std::lock_guard<std::mutex> lock(openmesh_mutex());
    SilenceOpenMesh silence;
    OpenMesh::IO::Options options;  // positions and faces only
    ok = OpenMesh::IO::IOManager().read(name, importer, options);
  }

  std::string format = ext.substr(1);
  std::transform(format.begin(), format.end(), format.begin(),
                 [](unsigned char c) { return char(std::toupper(c)); });
  if (!ok) fail("{}: OpenMesh cannot parse the file as {}", name, format);
  if (const auto [face, index] = importer.bad_index(); face != SIZE_MAX)
    fail("{}: face {} uses vertex {} but the file has {} vertices", name, face, index, soup.positions.size());
  if (expected.vertices && *expected.vertices != soup.positions.size())
    fail("{}: the file declares {} vertices but {} were read", name, *expected.vertices,
         soup.positions.size());
  if (expected.faces && *expected.faces != importer.faces_read())
    fail("{}: the file declares {} faces but {} were read", name, *expected.faces, importer.faces_read());
  if (soup.triangles.empty()) {
    if (importer.faces_read() > 0)
      fail("{}: no triangles: all {} faces have fewer than 3 vertices", name, importer.faces_read());
    fail("{}: no triangles found; is it a valid {} file?", name, format);
  }
  validate_soup(soup, name);
  return soup;
}

}  // namespace voxr
