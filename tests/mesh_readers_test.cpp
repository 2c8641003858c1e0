// voxr's own mesh readers (mesh/mesh_readers.h), systematically: PLY in every format, coordinate scalar
// type, list count type and index type, with properties and elements in every order; OBJ corner forms and
// statements; OFF colour columns, comments and line endings; STL ASCII, binary and its ambiguous cases.
// Every input is built here, and every error must be one line that starts with the file name and names the
// place (line, or element and property).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <bit>
#include <chrono>
#include <cmath>
#include <cstring>
#include <limits>
#include <numeric>
#include <string>
#include <vector>

#include "core/mesh_loader.h"
#include "mesh/mesh_readers.h"
#include "test_support.h"
#include "util/error.h"

namespace voxr {
namespace {

static_assert(std::endian::native == std::endian::little, "the binary writers below assume little-endian");

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

// ------------------------------------------------------------------------------------------------------
// What a file should hold, and how a read mesh differs from it.

struct Mesh {
  std::vector<glm::dvec3> positions;
  std::vector<std::vector<uint32_t>> faces;
};

std::string show(const glm::dvec3& p) {
  return fmt::format("({}, {}, {})", p.x, p.y, p.z);
}

// Empty when `got` holds exactly `want`'s positions and faces; otherwise the first difference.
std::string mismatch(const Mesh& want, const PolygonMesh& got) {
  if (got.positions.size() != want.positions.size())
    return fmt::format("{} positions, expected {}", got.positions.size(), want.positions.size());
  for (size_t i = 0; i < want.positions.size(); ++i)
    if (got.positions[i] != want.positions[i] ||
        std::signbit(got.positions[i].x) != std::signbit(want.positions[i].x) ||
        std::signbit(got.positions[i].y) != std::signbit(want.positions[i].y) ||
        std::signbit(got.positions[i].z) != std::signbit(want.positions[i].z))
      return fmt::format("position {} is {}, expected {}", i, show(got.positions[i]),
                         show(want.positions[i]));
  if (got.face_sizes.size() != want.faces.size())
    return fmt::format("{} faces, expected {}", got.face_sizes.size(), want.faces.size());
  size_t k = 0;
  for (size_t f = 0; f < want.faces.size(); ++f) {
    if (got.face_sizes[f] != want.faces[f].size())
      return fmt::format("face {} has {} corners, expected {}", f, got.face_sizes[f], want.faces[f].size());
    for (uint32_t c : want.faces[f]) {
      if (k >= got.indices.size()) return "fewer indices than face sizes";
      if (got.indices[k] != c)
        return fmt::format("face {}: corner index {}, expected {}", f, got.indices[k], c);
      ++k;
    }
  }
  if (k != got.indices.size()) return "more indices than face sizes";
  return "";
}

// The reader's result compared with `want`, or the message it threw.
template <typename Read>
std::string check(const Mesh& want, Read read) {
  try {
    return mismatch(want, read());
  } catch (const Error& e) {
    return std::string("threw: ") + e.what();
  }
}

template <typename Read>
std::string error_of(Read read) {
  try {
    read();
  } catch (const Error& e) {
    return e.what();
  }
  return "(no error)";
}

// A reader's message: one line, starting with `name: `, holding every one of `parts`.
void expect_message(const std::string& message, const std::string& name,
                    std::initializer_list<std::string> parts, const std::string& context = "") {
  EXPECT_EQ(message.rfind(name + ": ", 0), 0u) << context << "\nmessage: " << message;
  EXPECT_EQ(message.find('\n'), std::string::npos) << context << "\nmessage: " << message;
  for (const std::string& part : parts)
    EXPECT_NE(message.find(part), std::string::npos)
        << context << "\nmessage:  " << message << "\nexpected: " << part;
}

// A tetrahedron (0..3) and a quad (2, 3, 5, 4) over six vertices with coordinates from `values`.
Mesh tetra_and_quad(const std::vector<double>& values) {
  Mesh m;
  for (size_t i = 0; i < 6; ++i)
    m.positions.push_back({values[(3 * i) % values.size()], values[(3 * i + 1) % values.size()],
                           values[(3 * i + 2) % values.size()]});
  m.faces = {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {0, 3, 2}, {2, 3, 5, 4}};
  return m;
}

Mesh simple_mesh() {
  return tetra_and_quad({0.5, -1.25, 3.0, 0.0, 0.0009765625, 2.0, -7.0});  // exact in float
}

// ------------------------------------------------------------------------------------------------------
// A PLY writer for any layout: elements and properties in the order given, any type, any format.

enum class Ty { kI8, kU8, kI16, kU16, kI32, kU32, kF32, kF64 };
constexpr Ty kAllTypes[] = {Ty::kI8, Ty::kU8, Ty::kI16, Ty::kU16, Ty::kI32, Ty::kU32, Ty::kF32, Ty::kF64};
constexpr Ty kIntTypes[] = {Ty::kI8, Ty::kU8, Ty::kI16, Ty::kU16, Ty::kI32, Ty::kU32};

const char* type_name(Ty t, bool alias) {
  static const char* names[2][8] = {
      {"char", "uchar", "short", "ushort", "int", "uint", "float", "double"},
      {"int8", "uint8", "int16", "uint16", "int32", "uint32", "float32", "float64"}};
  return names[alias][int(t)];
}
bool is_float(Ty t) {
  return t == Ty::kF32 || t == Ty::kF64;
}
double type_max(Ty t) {
  constexpr double m[] = {127, 255, 32767, 65535, 2147483647.0, 4294967295.0};
  return m[int(t)];
}

// Values of type `t` (each exactly representable) used as coordinates; extremes of the integer types.
std::vector<double> values_of(Ty t) {
  switch (t) {
    case Ty::kI8:
      return {-128, 127, 0, 1, -1, 5, 3};
    case Ty::kU8:
      return {0, 255, 1, 128, 7, 2, 9};
    case Ty::kI16:
      return {-32768, 32767, 0, 258, -259, 1, 4};
    case Ty::kU16:
      return {0, 65535, 258, 1, 32768, 3, 17};
    case Ty::kI32:
      return {-2147483648.0, 2147483647.0, 0, 16909060, -16909061, 1, 2};
    case Ty::kU32:
      return {0, 4294967295.0, 16909060, 1, 2147483648.0, 5, 6};
    case Ty::kF32:
      return {0.5, -1.25, 3e7, double(std::numeric_limits<float>::denorm_min()), -65504, double(1.0f / 3.0f),
              -0.0};
    case Ty::kF64:
      return {0.1, -123456789.123456789, 1e-300, 1e30, -2.5, 1.0 / 3.0, -0.0};
  }
  return {};
}

enum class PlyFormat { kAscii, kLittle, kBig };
constexpr PlyFormat kPlyFormats[] = {PlyFormat::kAscii, PlyFormat::kLittle, PlyFormat::kBig};
const char* format_name(PlyFormat f) {
  static const char* names[] = {"ascii", "binary_little_endian", "binary_big_endian"};
  return names[int(f)];
}

struct Prop {
  std::string name;
  Ty type = Ty::kF32;  // of the scalar or of each list item
  bool list = false;
  Ty count_type = Ty::kU8;
};

struct Element {
  std::string name;
  std::vector<Prop> props;
  std::vector<std::vector<std::vector<double>>> rows;  // rows[i][k]: values of property k (one for a scalar)
};

// Where one value lies in the body (list counts and items included).
struct Span {
  std::string element;
  size_t index = 0, count = 0;
  std::string property;
  size_t begin = 0, end = 0;
};

struct PlyFile {
  std::string bytes;
  size_t body = 0;  // where the body starts
  std::vector<Span> spans;
};

void put(std::string& out, Ty t, double v, PlyFormat f) {
  if (f == PlyFormat::kAscii) {
    out += is_float(t) ? fmt::format("{}", t == Ty::kF32 ? double(float(v)) : v)
                       : fmt::format("{}", (long long)v);
    return;
  }
  unsigned char b[8];
  size_t n = 0;
  auto store = [&](auto x) {
    n = sizeof x;
    std::memcpy(b, &x, n);
  };
  switch (t) {
    case Ty::kI8:
      store(int8_t(v));
      break;
    case Ty::kU8:
      store(uint8_t(v));
      break;
    case Ty::kI16:
      store(int16_t(v));
      break;
    case Ty::kU16:
      store(uint16_t(v));
      break;
    case Ty::kI32:
      store(int32_t(v));
      break;
    case Ty::kU32:
      store(uint32_t(v));
      break;
    case Ty::kF32:
      store(float(v));
      break;
    case Ty::kF64:
      store(v);
      break;
  }
  if (f == PlyFormat::kBig) std::reverse(b, b + n);
  out.append(reinterpret_cast<const char*>(b), n);
}

// `chatty` puts comment and obj_info lines everywhere the header allows; `alias` spells types as int8 ...;
// `spans` records where each value lies.
PlyFile write_ply(PlyFormat f, const std::vector<Element>& elements, bool chatty = false, bool alias = false,
                  bool spans = false) {
  PlyFile file;
  std::string& s = file.bytes;
  s = fmt::format("ply\nformat {} 1.0\n", format_name(f));
  if (chatty) s += "comment written by mesh_readers_test\nobj_info any text: 1 2 3\n";
  for (const Element& e : elements) {
    s += fmt::format("element {} {}\n", e.name, e.rows.size());
    if (chatty) s += fmt::format("comment element {} follows\n", e.name);
    for (const Prop& p : e.props) {
      s += p.list ? fmt::format("property list {} {} {}\n", type_name(p.count_type, alias),
                                type_name(p.type, alias), p.name)
                  : fmt::format("property {} {}\n", type_name(p.type, alias), p.name);
      if (chatty) s += "obj_info between properties\n";
    }
  }
  s += "end_header\n";
  file.body = s.size();
  for (const Element& e : elements) {
    for (size_t i = 0; i < e.rows.size(); ++i) {
      bool first = true;
      auto value = [&](const Prop& p, Ty t, double v) {
        if (f == PlyFormat::kAscii && !first) s += ' ';
        first = false;
        const size_t begin = s.size();
        put(s, t, v, f);
        if (spans) file.spans.push_back({e.name, i, e.rows.size(), p.name, begin, s.size()});
      };
      for (size_t k = 0; k < e.props.size(); ++k) {
        const Prop& p = e.props[k];
        const std::vector<double>& v = e.rows[i][k];
        if (p.list) value(p, p.count_type, double(v.size()));
        for (double x : v) value(p, p.type, x);
      }
      if (f == PlyFormat::kAscii) s += '\n';
    }
  }
  return file;
}

// Values of a property that is neither coordinate nor index: NaN in every other float, small integers
// (which fit every integer type), lists of 0, 1 or 2 items.
std::vector<double> filler(const Prop& p, size_t i) {
  auto scalar = [&](size_t j) {
    return is_float(p.type) ? ((i + j) % 2 ? kNaN : 0.25 * double(i + j)) : double((7 * i + 3 * j) % 100);
  };
  std::vector<double> v(p.list ? i % 3 : 1);
  for (size_t j = 0; j < v.size(); ++j) v[j] = scalar(j);
  return v;
}

Element vertex_element(const Mesh& m, std::vector<Prop> props) {
  Element e{"vertex", std::move(props), {}};
  for (size_t i = 0; i < m.positions.size(); ++i) {
    auto& row = e.rows.emplace_back();
    for (const Prop& p : e.props) {
      const int axis = p.name == "x" ? 0 : p.name == "y" ? 1 : p.name == "z" ? 2 : -1;
      row.push_back(axis >= 0 ? std::vector<double>{m.positions[i][axis]} : filler(p, i));
    }
  }
  return e;
}

bool is_index_list(const Prop& p) {
  return p.name == "vertex_indices" || p.name == "vertex_index";
}

Element face_element(const Mesh& m, std::vector<Prop> props) {
  Element e{"face", std::move(props), {}};
  for (size_t i = 0; i < m.faces.size(); ++i) {
    auto& row = e.rows.emplace_back();
    for (const Prop& p : e.props)
      row.push_back(is_index_list(p) ? std::vector<double>(m.faces[i].begin(), m.faces[i].end())
                                     : filler(p, i));
  }
  return e;
}

Element other_element(std::string name, std::vector<Prop> props, size_t count) {
  Element e{std::move(name), std::move(props), {}};
  for (size_t i = 0; i < count; ++i) {
    auto& row = e.rows.emplace_back();
    for (const Prop& p : e.props) row.push_back(filler(p, i));
  }
  return e;
}

Prop scalar(std::string name, Ty t) {
  return {std::move(name), t, false, Ty::kU8};
}
Prop list(std::string name, Ty count, Ty item) {
  return {std::move(name), item, true, count};
}

std::vector<Prop> xyz(Ty t) {
  return {scalar("x", t), scalar("y", t), scalar("z", t)};
}

std::string context(PlyFormat f, const std::string& bytes) {
  return fmt::format("format {}, header:\n{}", format_name(f), bytes.substr(0, bytes.find("end_header")));
}

// ------------------------------------------------------------------------------------------------------
// PLY

TEST(MeshReadersPly, EveryFormatCoordinateTypeCountTypeAndIndexType) {
  int combination = 0;
  for (PlyFormat f : kPlyFormats)
    for (Ty coordinate : kAllTypes)
      for (Ty count : kIntTypes)
        for (Ty index : kIntTypes) {
          const Mesh m = tetra_and_quad(values_of(coordinate));
          const PlyFile file = write_ply(
              f,
              {vertex_element(m, xyz(coordinate)), face_element(m, {list("vertex_indices", count, index)})},
              false, combination++ % 2 == 1);
          EXPECT_EQ(check(m, [&] { return read_ply("t.ply", file.bytes); }), "") << context(f, file.bytes);
        }
}

// Indices and list counts whose high bytes are not zero: byte order and width of every index type.
TEST(MeshReadersPly, WideIndicesAndCountsOfEveryIntegerType) {
  for (Ty t : kIntTypes) {
    const uint32_t top = uint32_t(std::min(type_max(t), 66000.0));  // highest index used: 3 bytes for 32 bits
    const uint32_t corners = uint32_t(std::min(type_max(t), 300.0));
    Mesh m;
    for (uint32_t i = 0; i <= top; ++i)
      m.positions.push_back({double(i % 251), double(i % 241), double(i % 239)});
    m.faces = {{0, top, top - 1}, {top, 1, 2}};
    auto& polygon = m.faces.emplace_back();
    for (uint32_t c = 0; c < corners; ++c) polygon.push_back(top - c);
    const std::vector<Element> elements = {vertex_element(m, xyz(Ty::kU8)),
                                           face_element(m, {list("vertex_indices", t, t)})};
    for (PlyFormat f : kPlyFormats) {
      const PlyFile file = write_ply(f, elements);
      EXPECT_EQ(check(m, [&] { return read_ply("t.ply", file.bytes); }), "") << context(f, file.bytes);
    }
  }
}

// Vertex properties before, between and after x, y, z, in every order of six properties; the coordinates
// of three different types, other float properties holding NaN.
TEST(MeshReadersPly, EveryVertexPropertyOrder) {
  const Mesh m = tetra_and_quad({0.5, -1.25, 3.0, 0.0, 1e-3, 2.0, -7.0, 120.0});
  std::vector<Prop> props = {scalar("x", Ty::kF64),  scalar("y", Ty::kF32),  scalar("z", Ty::kI16),
                             scalar("nx", Ty::kF32), scalar("red", Ty::kU8), scalar("confidence", Ty::kF32)};
  // Round the coordinates to what their types hold: z as int16, y as float.
  Mesh want = m;
  for (auto& p : want.positions) p = {p.x, double(float(p.y)), std::round(p.z)};
  std::vector<int> order = {0, 1, 2, 3, 4, 5};
  int orders = 0;
  do {
    std::vector<Prop> ordered;
    for (int k : order) ordered.push_back(props[k]);
    for (PlyFormat f : kPlyFormats) {
      const PlyFile file = write_ply(
          f, {vertex_element(want, ordered), face_element(m, {list("vertex_indices", Ty::kU8, Ty::kI32)})});
      EXPECT_EQ(check(want, [&] { return read_ply("t.ply", file.bytes); }), "") << context(f, file.bytes);
    }
    ++orders;
  } while (std::next_permutation(order.begin(), order.end()));
  EXPECT_EQ(orders, 720);
}

// Face scalars (material_index, flags) and other lists (texcoord) before, after and around the index list,
// in every order, with 'vertex_indices' and 'vertex_index' as its name.
TEST(MeshReadersPly, EveryFacePropertyOrder) {
  const Mesh m = simple_mesh();
  for (const char* index_name : {"vertex_indices", "vertex_index"}) {
    std::vector<Prop> props = {list(index_name, Ty::kU8, Ty::kI32), scalar("material_index", Ty::kI32),
                               list("texcoord", Ty::kU8, Ty::kF32), scalar("flags", Ty::kU8)};
    std::vector<int> order = {0, 1, 2, 3};
    do {
      std::vector<Prop> ordered;
      for (int k : order) ordered.push_back(props[k]);
      for (PlyFormat f : kPlyFormats) {
        const PlyFile file = write_ply(f, {vertex_element(m, xyz(Ty::kF32)), face_element(m, ordered)});
        EXPECT_EQ(check(m, [&] { return read_ply("t.ply", file.bytes); }), "") << context(f, file.bytes);
      }
    } while (std::next_permutation(order.begin(), order.end()));
  }
}

// The reported case: a face scalar before the index list.
TEST(MeshReadersPly, MaterialIndexBeforeVertexIndices) {
  const Mesh m = simple_mesh();
  for (PlyFormat f : kPlyFormats) {
    const PlyFile file = write_ply(
        f, {vertex_element(m, xyz(Ty::kF32)),
            face_element(m, {scalar("material_index", Ty::kI32), list("vertex_indices", Ty::kU8, Ty::kI32),
                             scalar("material_index2", Ty::kU16)})});
    EXPECT_EQ(check(m, [&] { return read_ply("t.ply", file.bytes); }), "") << context(f, file.bytes);
  }
}

// Other elements ('edge', 'material') before, between and after vertex and face, in every order of the
// four; comment and obj_info lines all through the header.
TEST(MeshReadersPly, EveryElementOrderWithCommentsAndObjInfo) {
  const Mesh m = simple_mesh();
  std::vector<Element> elements = {
      vertex_element(
          m, {scalar("x", Ty::kF32), scalar("nx", Ty::kF32), scalar("y", Ty::kF32), scalar("z", Ty::kF32)}),
      face_element(m, {list("vertex_indices", Ty::kU8, Ty::kU32), scalar("material_index", Ty::kI32)}),
      other_element("edge",
                    {scalar("vertex1", Ty::kI32), scalar("vertex2", Ty::kI32), scalar("crease", Ty::kU8)}, 5),
      other_element(
          "material",
          {scalar("ambient_red", Ty::kU8), list("name", Ty::kU8, Ty::kI8), scalar("shininess", Ty::kF32)},
          4)};
  std::vector<int> order = {0, 1, 2, 3};
  do {
    std::vector<Element> ordered;
    for (int k : order) ordered.push_back(elements[k]);
    for (PlyFormat f : kPlyFormats) {
      const PlyFile file = write_ply(f, ordered, true);
      EXPECT_EQ(check(m, [&] { return read_ply("t.ply", file.bytes); }), "") << context(f, file.bytes);
    }
  } while (std::next_permutation(order.begin(), order.end()));
}

// ASCII specifics: NaN spelled in any case in a non-coordinate property, CRLF lines, extra spaces.
TEST(MeshReadersPly, AsciiNaNPropertiesCrlfAndSpacing) {
  const std::string text =
      "ply\r\nformat ascii 1.0\r\ncomment crlf\r\nelement vertex 3\r\nproperty float confidence\r\n"
      "property float x\r\nproperty float y\r\nproperty float z\r\nproperty float quality\r\n"
      "element face 1\r\nproperty list uchar int vertex_indices\r\nend_header\r\n"
      "nan 0 0 0 NaN\r\n-nan  1 0 0\tinf\r\nNAN 0 1 0 -inf\r\n3 0 1 2\r\n";
  Mesh want;
  want.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  want.faces = {{0, 1, 2}};
  EXPECT_EQ(check(want, [&] { return read_ply("t.ply", text); }), "");
}

std::string ply_error(const std::string& bytes) {
  return error_of([&] { return read_ply("bad.ply", bytes); });
}

// ASCII: a header that declares fewer properties than the lines hold would shift every later value; the
// line, element and index are named instead.
TEST(MeshReadersPly, AsciiRowWithMoreValuesThanPropertiesFails) {
  const Mesh m = simple_mesh();
  const PlyFile file = write_ply(
      PlyFormat::kAscii,
      {vertex_element(
           m, {scalar("x", Ty::kF32), scalar("y", Ty::kF32), scalar("z", Ty::kF32), scalar("nx", Ty::kF32)}),
       face_element(m, {list("vertex_indices", Ty::kU8, Ty::kI32), scalar("material_index", Ty::kI32)})});
  auto without = [&](const std::string& line) {
    std::string s = file.bytes;
    s.erase(s.find(line), line.size());
    return s;
  };
  // Header lines 1-10 (11 with nx): vertices from line 12, faces from line 18.
  expect_message(ply_error(without("property float nx\n")), "bad.ply",
                 {"line 11: vertex 0 of 6 has more values than its 3 properties"});
  expect_message(ply_error(without("property int material_index\n")), "bad.ply",
                 {"line 17: face 0 of 5 has more values than its 1 properties"});
  std::string one = file.bytes;  // one extra value on the line of vertex 3
  size_t at = file.body;
  for (int row = 0; row < 4; ++row) at = one.find('\n', at) + 1;
  one.insert(at - 1, " 7");
  expect_message(ply_error(one), "bad.ply", {"line 15: vertex 3 of 6 has more values than its 4 properties"});
  // Spaces, tabs and CR at line ends are no values.
  std::string spaces = file.bytes;
  spaces.insert(at - 1, " \t \r");
  EXPECT_EQ(check(m, [&] { return read_ply("t.ply", spaces); }), "");
}

// Header errors: each names the element and property.
TEST(MeshReadersPly, HeaderErrorsNameElementAndProperty) {
  const Mesh m = simple_mesh();
  for (PlyFormat f : kPlyFormats) {
    auto file = [&](std::vector<Prop> vertex, std::vector<Prop> face) {
      return write_ply(f, {vertex_element(m, std::move(vertex)), face_element(m, std::move(face))}).bytes;
    };
    const Prop indices = list("vertex_indices", Ty::kU8, Ty::kI32);
    const std::string ctx = format_name(f);
    expect_message(ply_error(file({scalar("x", Ty::kF32), scalar("z", Ty::kF32)}, {indices})), "bad.ply",
                   {"element 'vertex' has no property 'y'"}, ctx);
    expect_message(ply_error(file({scalar("y", Ty::kF32), scalar("z", Ty::kF32)}, {indices})), "bad.ply",
                   {"element 'vertex' has no property 'x'"}, ctx);
    expect_message(ply_error(file({scalar("x", Ty::kF32), scalar("y", Ty::kF32)}, {indices})), "bad.ply",
                   {"element 'vertex' has no property 'z'"}, ctx);
    expect_message(
        ply_error(
            file({scalar("x", Ty::kF32), list("y", Ty::kU8, Ty::kF32), scalar("z", Ty::kF32)}, {indices})),
        "bad.ply", {"element 'vertex' property 'y' is a list"}, ctx);
    expect_message(ply_error(file(xyz(Ty::kF32), {list("corners", Ty::kU8, Ty::kI32)})), "bad.ply",
                   {"element 'face' has no list property 'vertex_indices'"}, ctx);
    expect_message(ply_error(file(xyz(Ty::kF32), {scalar("vertex_indices", Ty::kI32)})), "bad.ply",
                   {"element 'face' property 'vertex_indices' is a scalar"}, ctx);
    for (Ty t : {Ty::kF32, Ty::kF64})
      expect_message(ply_error(file(xyz(Ty::kF32), {list("vertex_indices", Ty::kU8, t)})), "bad.ply",
                     {"element 'face' property 'vertex_indices' has a floating-point item type"}, ctx);
    std::string unknown = file(xyz(Ty::kF32), {indices});
    unknown.replace(unknown.find("property float y"), 16, "property float16 y");
    expect_message(ply_error(unknown), "bad.ply",
                   {"element 'vertex' property 'y' has unknown PLY type 'float16'"}, ctx);
    std::string unknown_item = file(xyz(Ty::kF32), {indices});
    unknown_item.replace(unknown_item.find("list uchar int"), 14, "list uchar integer");
    expect_message(ply_error(unknown_item), "bad.ply",
                   {"element 'face' property 'vertex_indices' has unknown PLY type 'integer'"}, ctx);
    for (const char* count : {"float", "double", "float32", "quad"}) {
      std::string float_count = file(xyz(Ty::kF32), {indices});
      float_count.replace(float_count.find("list uchar"), 10, std::string("list ") + count);
      expect_message(
          ply_error(float_count), "bad.ply",
          {"element 'face' property 'vertex_indices': a list count must have an integer type, not '" +
           std::string(count) + "'"},
          ctx);
    }
  }
  expect_message(ply_error("ply\nformat ascii 1.0\nelement face 0\nproperty list uchar int vertex_indices\n"
                           "end_header\n"),
                 "bad.ply", {"no 'vertex' element"});
  expect_message(ply_error("ply\nformat ascii 1.0\nelement vertex 0\nproperty float x\nproperty float y\n"
                           "property float z\nend_header\n"),
                 "bad.ply", {"no 'face' element"});
}

// Body errors: negative and out-of-range indices, non-finite coordinates, values outside their type.
TEST(MeshReadersPly, BodyErrorsNameElementIndexAndProperty) {
  for (PlyFormat f : kPlyFormats) {
    const std::string ctx = format_name(f);
    for (Ty t : {Ty::kI8, Ty::kI16, Ty::kI32}) {
      Mesh m = simple_mesh();
      m.faces[3] = {0, uint32_t(-1), 2};  // written as -1 in a signed type
      Element faces =
          face_element(m, {scalar("material_index", Ty::kI32), list("vertex_indices", Ty::kU8, t)});
      faces.rows[3][1][1] = -1;
      const PlyFile file = write_ply(f, {vertex_element(m, xyz(Ty::kF32)), faces});
      expect_message(ply_error(file.bytes), "bad.ply",
                     {"face 3 of 5, property 'vertex_indices'", "negative value -1"}, ctx);
    }
    for (Ty t : kIntTypes) {
      Mesh m = simple_mesh();
      m.faces[4][2] = uint32_t(std::min(type_max(t), 6.0 + double(int(t))));
      const PlyFile file = write_ply(
          f, {vertex_element(m, xyz(Ty::kF32)), face_element(m, {list("vertex_indices", Ty::kU8, t)})});
      expect_message(ply_error(file.bytes), "bad.ply",
                     {"face 4 of 5, property 'vertex_indices'",
                      fmt::format("vertex index {} but the file has 6 vertices", m.faces[4][2])},
                     ctx);
    }
    for (Ty t : {Ty::kI8, Ty::kI16, Ty::kI32}) {  // a negative list count
      const Mesh m = simple_mesh();
      Element faces = face_element(m, {list("vertex_indices", t, Ty::kI32)});
      PlyFile file = write_ply(f, {vertex_element(m, xyz(Ty::kF32)), faces}, false, false, true);
      const Span& count = *std::find_if(file.spans.begin(), file.spans.end(),
                                        [](const Span& s) { return s.element == "face" && s.index == 2; });
      std::string negative;
      put(negative, t, -3, f);
      file.bytes.replace(count.begin, count.end - count.begin, negative);
      expect_message(ply_error(file.bytes), "bad.ply",
                     {"face 2 of 5, property 'vertex_indices'", "negative value -3"}, ctx);
    }
    for (Ty t : {Ty::kF32, Ty::kF64})
      for (double bad : {kNaN, kInf, -kInf, 1e31}) {
        if (t == Ty::kF32 && bad == 1e31) continue;
        Mesh m = simple_mesh();
        m.positions[4].y = bad;
        const PlyFile file = write_ply(
            f, {vertex_element(m, {scalar("nx", Ty::kF32), scalar("x", t), scalar("y", t), scalar("z", t)}),
                face_element(m, {list("vertex_indices", Ty::kU8, Ty::kI32)})});
        expect_message(ply_error(file.bytes), "bad.ply",
                       {fmt::format("vertex 4 of 6, property 'y': {} is not a finite coordinate", bad)}, ctx);
      }
  }
  // ASCII: values that are no number, or outside their integer type, or fractional where integers belong.
  const std::string head =
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty uchar y\nproperty float z\n"
      "element face 1\nproperty list uchar short vertex_indices\nend_header\n";
  expect_message(ply_error(head + "0 0 0\n1 0 zero\n0 1 0\n3 0 1 2\n"), "bad.ply",
                 {"line 11: vertex 1 of 3, property 'z': 'zero' is not a number"});
  expect_message(ply_error(head + "0 0 0\n1 256 0\n0 1 0\n3 0 1 2\n"), "bad.ply",
                 {"line 11: vertex 1 of 3, property 'y': '256' is not a value of the declared integer type"});
  expect_message(
      ply_error(head + "0 0 0\n1 -1 0\n0 1 0\n3 0 1 2\n"), "bad.ply",
      {"line 11: vertex 1 of 3, property 'y'", "'-1' is not a value of the declared integer type"});
  expect_message(ply_error(head + "0 0 0\n1 0 0\n0 1 0\n3 0 1.5 2\n"), "bad.ply",
                 {"line 13: face 0 of 1, property 'vertex_indices'", "'1.5'"});
  expect_message(ply_error(head + "0 0 0\n1 0 0\n0 1 0\n3 0 1 40000\n"), "bad.ply",
                 {"line 13: face 0 of 1, property 'vertex_indices'", "'40000'"});
}

// A body cut anywhere: the message names the element, its index and the property whose value is missing.
TEST(MeshReadersPly, TruncatedBodyNamesElementIndexAndProperty) {
  const Mesh m = simple_mesh();
  for (PlyFormat f : kPlyFormats) {
    const PlyFile file = write_ply(
        f,
        {vertex_element(m, {scalar("x", Ty::kF64), scalar("red", Ty::kU8), scalar("y", Ty::kF32),
                            scalar("z", Ty::kI16)}),
         other_element("edge", {scalar("vertex1", Ty::kI32), scalar("vertex2", Ty::kU16)}, 2),
         face_element(m, {scalar("material_index", Ty::kI32), list("vertex_indices", Ty::kU16, Ty::kU32),
                          list("texcoord", Ty::kU8, Ty::kF32)})},
        false, false, true);
    ASSERT_GT(file.spans.size(), 50u);
    for (const Span& s : file.spans) {
      // ASCII: cut just before the value; binary: cut at every byte of it.
      const size_t last = f == PlyFormat::kAscii ? s.begin + 1 : s.end;
      for (size_t cut = s.begin; cut < last; ++cut) {
        const std::string message = ply_error(file.bytes.substr(0, cut));
        expect_message(message, "bad.ply",
                       {fmt::format("{} {} of {}, property '{}': the file ends here", s.element, s.index,
                                    s.count, s.property)},
                       fmt::format("{}: cut at body byte {}", format_name(f), cut - file.body));
      }
    }
  }
}

// Headers announcing billions of elements over a tiny body fail at once, without allocating for them.
TEST(MeshReadersPly, HugeCountsWithTinyBodyFailFast) {
  for (PlyFormat f : kPlyFormats) {
    const Mesh m = simple_mesh();
    const std::string ctx = format_name(f);
    const std::string bytes = write_ply(f, {vertex_element(m, xyz(Ty::kF32)),
                                            face_element(m, {list("vertex_indices", Ty::kU8, Ty::kI32)})})
                                  .bytes;
    auto with_count = [&](const std::string& element, const std::string& count) {
      std::string s = bytes;
      const std::string line = "element " + element + " ";
      const size_t at = s.find(line) + line.size();
      s.replace(at, s.find('\n', at) - at, count);
      return s;
    };
    const auto start = std::chrono::steady_clock::now();
    expect_message(ply_error(with_count("vertex", "4000000000")), "bad.ply",
                   {"4000000000 vertices are more than voxr can index"}, ctx);
    // The faces' values are read as vertices until the body ends (or, in ASCII, a face line holds more
    // values than a vertex has).
    expect_message(ply_error(with_count("vertex", "2000000000")), "bad.ply",
                   {f == PlyFormat::kAscii ? "vertex 6 of 2000000000 has more values than its 3 properties"
                                           : "of 2000000000, property 'z': the file ends here"},
                   ctx);
    expect_message(ply_error(with_count("face", "4000000000")), "bad.ply",
                   {"face 5 of 4000000000, property 'vertex_indices': the file ends here"}, ctx);
    expect_message(ply_error(with_count("vertex", "99999999999999999999999")), "bad.ply",
                   {"line 3: the element count '99999999999999999999999' is not a non-negative integer"},
                   ctx);
    // An element without properties takes no bytes, so any count of it is consistent, and quick (reading
    // took 10 s per 4e9 before, and 2^64 - 1 would never end: tried only once 4e9 passed).
    std::string empty = bytes;
    empty.insert(empty.find("element face"), "element nothing 4000000000\n");
    EXPECT_EQ(check(m, [&] { return read_ply("t.ply", empty); }), "") << ctx;
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    ASSERT_LT(seconds, 0.5) << ctx;
    empty.insert(empty.find("element face"), "element void 18446744073709551615\n");
    EXPECT_EQ(check(m, [&] { return read_ply("t.ply", empty); }), "") << ctx;
  }
}

// ------------------------------------------------------------------------------------------------------
// OBJ

enum class Corner { kV, kVVt, kVVn, kVVtVn };

// Vertices written just before the first face that needs them, so that negative (relative) indices
// resolve against different counts.
std::string obj_text(const Mesh& m, Corner form, bool negative) {
  std::string s = "# test mesh\nmtllib test.mtl\no thing\n";
  size_t written = 0;
  for (const auto& face : m.faces) {
    const size_t need = *std::max_element(face.begin(), face.end()) + 1;
    for (; written < need; ++written) {
      const glm::dvec3& p = m.positions[written];
      s += fmt::format("v {} {} {}\nvt 0.5 0.5\nvn 0 0 1\n", p.x, p.y, p.z);
    }
    s += "usemtl red\ns 1\nf";
    for (uint32_t c : face) {
      const long long v = negative ? (long long)c - (long long)written : (long long)c + 1;
      const long long t = negative ? -1 : 1;
      switch (form) {
        case Corner::kV:
          s += fmt::format(" {}", v);
          break;
        case Corner::kVVt:
          s += fmt::format(" {}/{}", v, t);
          break;
        case Corner::kVVn:
          s += fmt::format(" {}//{}", v, t);
          break;
        case Corner::kVVtVn:
          s += fmt::format(" {}/{}/{}", v, t, t);
          break;
      }
    }
    s += '\n';
  }
  return s;
}

TEST(MeshReadersObj, EveryCornerFormPositiveAndNegative) {
  const Mesh m = simple_mesh();
  for (Corner form : {Corner::kV, Corner::kVVt, Corner::kVVn, Corner::kVVtVn})
    for (bool negative : {false, true}) {
      const std::string text = obj_text(m, form, negative);
      EXPECT_EQ(check(m, [&] { return read_obj("t.obj", text); }), "") << text;
    }
}

TEST(MeshReadersObj, PolygonsWAndColoursIgnoredStatementsAndCrlf) {
  Mesh want;
  want.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0.5, 1.5, 0}, {0, 1, 0}, {0.25, 0.5, 1e-9}};
  want.faces = {{0, 1, 2, 3, 4}, {0, 1, 5}, {5, 4, 3, 2, 1, 0}};
  for (bool crlf : {false, true}) {
    std::string text =
        "# comment\n"
        "mtllib a.mtl\n"
        "v 0 0 0 1.0\n"              // w
        "v 1 0 0 0.5 0.25 1\n"       // colour
        "v 1 1 0 0.1 0.2 0.3 1.0\n"  // colour and w
        "v\t0.5  1.5 0 # trailing comment\n"
        "v 0 1 0\n"
        "v 0.25 0.5 1e-9\n"
        "vt 0 0\nvn 0 0 1\nvp 0.5\n"
        "g group1 group2\no object\nusemtl mat\ns off\ns 1\n"
        "l 1 2 3\np 1 2\n"
        "f 1 2 3 4 5\n"
        "\n"
        "   \n"
        "f 1/1 2/1 6/1 # a triangle\n"
        "fo -1//1 -2//1 -3//1 -4//1 -5//1 -6//1\n";
    if (crlf) {
      std::string out;
      for (char c : text) out += c == '\n' ? std::string("\r\n") : std::string(1, c);
      text = out;
    }
    EXPECT_EQ(check(want, [&] { return read_obj("t.obj", text); }), "") << (crlf ? "CRLF" : "LF");
  }
}

// Issue 20, kind 5: `usemtl` names number the faces' materials in the order faces first use them; the faces
// before any `usemtl` (and after a bare one) count as one more name. One name in all: no ids.
TEST(MeshReadersObj, UsemtlGroupsNumberMaterialsInOrderOfFirstUse) {
  const std::string v = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\n";
  EXPECT_EQ(read_obj("m.obj", v + "f 1 2 3\nusemtl red\nf 1 2 4\nusemtl dark blue\nf 1 3 4\n"
                                  "usemtl red\nf 2 3 4\nf 1 2 3\nusemtl\nf 1 2 4\n")
                .materials,
            (std::vector<uint32_t>{0, 1, 2, 1, 1, 0}));
  // A name used first by no face takes no id; a group of faces after several usemtl lines gets the last.
  EXPECT_EQ(read_obj("m.obj", v + "usemtl unused\nusemtl b\nf 1 2 3\nusemtl a\nf 1 2 4\nusemtl b\nf 1 3 4\n")
                .materials,
            (std::vector<uint32_t>{0, 1, 0}));
  EXPECT_TRUE(read_obj("m.obj", v + "usemtl only\nf 1 2 3\nf 1 2 4\n").materials.empty());
  EXPECT_TRUE(read_obj("m.obj", v + "f 1 2 3\nusemtl later\n").materials.empty());
}

TEST(MeshReadersObj, ErrorsNameTheLine) {
  const std::string head = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\n# faces\n";  // lines 1-5
  auto obj_error = [](const std::string& text) {
    return error_of([&] { return read_obj("bad.obj", text); });
  };
  struct Case {
    std::string face;
    std::string expected;
  };
  const Case cases[] = {
      {"f 1 2 0", "line 6: face corner '0' refers to vertex 0 but 4 vertices are defined before it"},
      {"f 1 2 5", "line 6: face corner '5' refers to vertex 5 but 4 vertices are defined before it"},
      {"f 1 2 5/1/1", "line 6: face corner '5/1/1' refers to vertex 5"},
      {"f -1 -2 -5", "line 6: face corner '-5' refers to vertex -5 but 4 vertices are defined before it"},
      {"f -1 -2 -5//1", "line 6: face corner '-5//1' refers to vertex -5"},
      {"f 1 2 x", "line 6: face corner 'x' does not start with a vertex index"},
      {"f 1 2 /3", "line 6: face corner '/3' does not start with a vertex index"},
      {"f 1 2 3x", "line 6: face corner '3x' does not start with a vertex index"},
      {"f 1 2 3.0", "line 6: face corner '3.0' does not start with a vertex index"},
      {"f 1 2 99999999999999999999", "line 6: face corner '99999999999999999999' does not start"},
  };
  for (const Case& c : cases)
    expect_message(obj_error(head + c.face + "\n"), "bad.obj", {c.expected}, c.face);
  // A face may only use vertices defined before it.
  expect_message(obj_error("v 0 0 0\nv 1 0 0\nf 1 2 3\nv 0 1 0\n"), "bad.obj",
                 {"line 3: face corner '3' refers to vertex 3 but 2 vertices are defined before it"});
  for (const char* bad : {"nan", "NaN", "inf", "-inf", "1e400", "1e31", "0x1p3", "1,5", "--1"})
    expect_message(obj_error(fmt::format("v 0 0 0\nv 1 0 0\n\nv 0 {} 0\nf 1 2 3\n", bad)), "bad.obj",
                   {fmt::format("line 4: vertex coordinate '{}' is not a finite number", bad)}, bad);
  expect_message(obj_error("v 0 0 0\r\nv 1 0\r\nv 0 1 0\r\nf 1 2 3\r\n"), "bad.obj",
                 {"line 2: a vertex needs three coordinates"});
}

// ------------------------------------------------------------------------------------------------------
// OFF

enum class Colour { kNone, kInt3, kInt4, kFloat3, kFloat4 };
constexpr Colour kColours[] = {Colour::kNone, Colour::kInt3, Colour::kInt4, Colour::kFloat3, Colour::kFloat4};

std::string colour_columns(Colour c, size_t i) {
  switch (c) {
    case Colour::kNone:
      return "";
    case Colour::kInt3:
      return fmt::format(" {} 128 0", i * 40 % 256);
    case Colour::kInt4:
      return fmt::format(" {} 128 0 255", i * 40 % 256);
    case Colour::kFloat3:
      return fmt::format(" {} 0.5 0", double(i % 4) / 4);
    case Colour::kFloat4:
      return fmt::format(" {} 0.5 0 1.0", double(i % 4) / 4);
  }
  return "";
}

struct OffStyle {
  Colour vertex = Colour::kNone, face = Colour::kNone;
  bool comments = false, crlf = false, counts_on_keyword_line = false;
  // Face numbers of ten digits (leading zeros): the fast scanner hands such lines to the token reader, so
  // both read every colour variant.
  bool padded = false;
};

std::string off_text(const Mesh& m, const OffStyle& st) {
  const std::string keyword = st.vertex == Colour::kNone ? "OFF" : "COFF";
  const std::string note = st.comments ? " # note" : "";
  std::string s;
  const std::string counts = fmt::format("{} {} 0", m.positions.size(), m.faces.size());
  if (st.counts_on_keyword_line) {
    s = keyword + " " + counts + note + "\n";
  } else {
    s = keyword + note + "\n" + (st.comments ? "# a comment line\n\n" : "") + counts + note + "\n";
  }
  for (size_t i = 0; i < m.positions.size(); ++i) {
    const glm::dvec3& p = m.positions[i];
    if (st.comments && i == 2) s += "# vertex 2 follows\n   \n";
    s += fmt::format("{} {} {}{}{}\n", p.x, p.y, p.z, colour_columns(st.vertex, i), note);
  }
  for (size_t f = 0; f < m.faces.size(); ++f) {
    if (st.comments && f == 1) s += "\t# face 1 follows\n";
    const int width = st.padded ? 10 : 1;
    s += fmt::format("{:0{}}", m.faces[f].size(), width);
    for (uint32_t c : m.faces[f]) s += fmt::format(" {:0{}}", c, width);
    s += colour_columns(st.face, f) + note + "\n";
  }
  if (st.comments) s += "# the end\n";
  if (st.crlf) {
    std::string out;
    for (char c : s) out += c == '\n' ? std::string("\r\n") : std::string(1, c);
    s = out;
  }
  return s;
}

TEST(MeshReadersOff, ColourColumnsCommentsCountsAndLineEndings) {
  const Mesh m = simple_mesh();
  for (Colour vertex : kColours)
    for (Colour face : {Colour::kNone, Colour::kInt3, Colour::kFloat4, Colour::kInt4})
      for (int bits = 0; bits < 16; ++bits) {
        const OffStyle st{vertex, face, (bits & 1) != 0, (bits & 2) != 0, (bits & 4) != 0, (bits & 8) != 0};
        const std::string text = off_text(m, st);
        EXPECT_EQ(check(m, [&] { return read_off("t.off", text); }), "") << text;
      }
}

TEST(MeshReadersOff, NormalAndTextureColumns) {
  const Mesh m = simple_mesh();
  std::string text = "NOFF\n6 5 12\n";
  for (const auto& p : m.positions) text += fmt::format("{} {} {} 0 0 1\n", p.x, p.y, p.z);
  for (const auto& f : m.faces) {
    text += std::to_string(f.size());
    for (uint32_t c : f) text += fmt::format(" {}", c);
    text += "\n";
  }
  EXPECT_EQ(check(m, [&] { return read_off("t.off", text); }), "");
  std::string st = text;
  st.replace(0, 4, "STCNOFF");
  EXPECT_EQ(check(m, [&] { return read_off("t.off", st); }), "");
}

// Over a megabyte, the body is read by two threads; colours, comments and CRLF must read the same.
TEST(MeshReadersOff, LargeColouredFileReadsLikeSmall) {
  Mesh m;
  const uint32_t n = 30000;
  for (uint32_t i = 0; i < n; ++i) m.positions.push_back({i * 0.5, -double(i % 977), 1.0 / (i + 1)});
  for (uint32_t i = 0; i + 3 < n; i += 2) m.faces.push_back({i, i + 1, i + 3, i + 2});
  const OffStyle st{Colour::kFloat4, Colour::kInt3, true, true, true};
  const std::string text = off_text(m, st);
  ASSERT_GT(text.size(), size_t(1) << 20);
  EXPECT_EQ(check(m, [&] { return read_off("t.off", text); }), "");
}

TEST(MeshReadersOff, ErrorsNameTheLine) {
  auto off_error = [](const std::string& text) {
    return error_of([&] { return read_off("bad.off", text); });
  };
  // Lines: 1 keyword, 2 comment, 3 counts, 4-6 vertices, 7 face.
  const std::string head = "COFF\n# comment\n3 1 0\n";
  struct Case {
    std::string body;
    std::string expected;
  };
  const Case cases[] = {
      {"0 0 0 255 0 0\n1 0 zero 0 0 0\n0 1 0\n3 0 1 2\n", "line 5: 'zero' is not a finite number"},
      {"0 0 0\n1 0 0 red\n0 1 0\n3 0 1 2\n", "line 5: 'red' is not a finite number"},
      {"0 0 0\n1 0\n0 1 0\n3 0 1 2\n", "line 5: vertex 1 needs three coordinates"},
      {"0 0 0\n1 0 0\nnan 1 0\n3 0 1 2\n", "line 6: 'nan' is not a finite number"},
      {"0 0 0\n1 0 0\n0 1 inf # c\n3 0 1 2\n", "line 6: 'inf' is not a finite number"},
      {"0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n", "line 7: face 0 uses vertex '3' but the file has 3 vertices"},
      {"0 0 0\n1 0 0\n0 1 0\n3 0 -1 2\n", "line 7: face 0 uses vertex '-1' but the file has 3 vertices"},
      {"0 0 0\n1 0 0\n0 1 0\n4 0 1 2\n", "line 7: face 0 lists fewer than 4 vertices"},
      {"0 0 0\n1 0 0\n0 1 0\n3.5 0 1 2\n",
       "line 7: the face vertex count '3.5' is not a non-negative integer"},
      {"0 0 0\n1 0 0\n0 1 0\n3 0 1 2 x\n", "line 7: 'x' is not a finite number"},
      {"0 0 0\n1 0 0\n\n# gap\n0 1 0\n3 0 1 2.5\n", "line 9: face 0 uses vertex '2.5'"},
      {"0 0 0\r\n1 0 0\r\n0 1 0\r\n3 0 1 9\r\n",
       "line 7: face 0 uses vertex '9' but the file has 3 vertices"},
      {"0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n0 0 x\n", "line 8: 'x' is not a finite number"},
      {"0 0 0\n1 0 0\n", "the file declares 3 vertices but ends after 2"},
      {"0 0 0\n1 0 0\n0 1 0\n", "the file declares 1 faces but ends after 0"},
  };
  for (const Case& c : cases) expect_message(off_error(head + c.body), "bad.off", {c.expected}, c.body);
  expect_message(off_error("OFF\n3 x 0\n"), "bad.off",
                 {"line 2: the face count 'x' is not a non-negative integer"});
  expect_message(off_error("OFF 3 1 0 0\n"), "bad.off", {"line 1: unexpected text after the OFF counts"});
  expect_message(off_error("PLY\n"), "bad.off", {"line 1: an OFF file starts with the keyword OFF"});
}

// ------------------------------------------------------------------------------------------------------
// STL

using Triangle = std::array<glm::vec3, 3>;

// The unit cube as 12 triangles (6 quads, two each).
std::vector<Triangle> cube_triangles(glm::vec3 offset = glm::vec3(0.0f)) {
  const int quads[6][4] = {{0, 4, 6, 2}, {1, 3, 7, 5}, {0, 1, 5, 4},
                           {2, 6, 7, 3}, {0, 2, 3, 1}, {4, 5, 7, 6}};
  auto corner = [&](int i) { return offset + glm::vec3(i & 1, (i >> 1) & 1, (i >> 2) & 1); };
  std::vector<Triangle> t;
  for (const auto& q : quads) {
    t.push_back({corner(q[0]), corner(q[1]), corner(q[2])});
    t.push_back({corner(q[0]), corner(q[2]), corner(q[3])});
  }
  return t;
}

std::string ascii_solid(const std::string& name, const std::vector<Triangle>& tris, size_t from, size_t to) {
  std::string s = "solid " + name + "\n";
  for (size_t t = from; t < to; ++t) {
    s += "  facet normal 0 0 0\n    outer loop\n";
    for (const glm::vec3& p : tris[t]) s += fmt::format("      vertex {} {} {}\n", p.x, p.y, p.z);
    s += "    endloop\n  endfacet\n";
  }
  return s + "endsolid " + name + "\n";
}

// Binary STL: `header` padded to 80 bytes, the triangle count (announced, default the real one), the
// triangles and `trailing` extra bytes.
std::string binary_stl(const std::vector<Triangle>& tris, std::string header = "binary", size_t trailing = 0,
                       int64_t announced = -1) {
  header.resize(80, ' ');
  std::string s = header;
  const uint32_t n = announced < 0 ? uint32_t(tris.size()) : uint32_t(announced);
  s.append(reinterpret_cast<const char*>(&n), 4);
  for (const Triangle& t : tris) {
    float f[12] = {0, 0, 1};
    for (int c = 0; c < 3; ++c)
      for (int a = 0; a < 3; ++a) f[3 + 3 * c + a] = t[c][a];
    s.append(reinterpret_cast<const char*>(f), sizeof f);
    s.append("\x01\x02", 2);
  }
  return s + std::string(trailing, '\0');
}

// Every triangle's corners are where the triangles say, and there are `positions` distinct positions.
std::string stl_mismatch(const std::vector<Triangle>& tris, const PolygonMesh& mesh, size_t positions) {
  if (mesh.positions.size() != positions)
    return fmt::format("{} positions, expected {}", mesh.positions.size(), positions);
  if (mesh.face_sizes.size() != tris.size())
    return fmt::format("{} faces, expected {}", mesh.face_sizes.size(), tris.size());
  for (size_t t = 0; t < tris.size(); ++t) {
    if (mesh.face_sizes[t] != 3) return fmt::format("face {} has {} corners", t, mesh.face_sizes[t]);
    for (int c = 0; c < 3; ++c)
      if (mesh.positions[mesh.indices[3 * t + c]] != glm::dvec3(tris[t][c]))
        return fmt::format("triangle {} corner {} is {}", t, c,
                           show(mesh.positions[mesh.indices[3 * t + c]]));
  }
  return "";
}

std::string stl_check(const std::vector<Triangle>& tris, const std::string& bytes, size_t positions,
                      std::vector<std::string>& notes) {
  try {
    return stl_mismatch(tris, read_stl("t.stl", bytes, notes), positions);
  } catch (const Error& e) {
    return std::string("threw: ") + e.what();
  }
}

TEST(MeshReadersStl, AsciiWithSeveralSolids) {
  std::vector<Triangle> tris = cube_triangles();
  const std::vector<Triangle> second = cube_triangles(glm::vec3(2.5f, 0.0f, -1.0f));
  tris.insert(tris.end(), second.begin(), second.end());
  const std::string text = ascii_solid("a", tris, 0, 5) + ascii_solid("b", tris, 5, 12) + "\n" +
                           ascii_solid("second cube", tris, 12, 24);
  std::vector<std::string> notes;
  EXPECT_EQ(stl_check(tris, text, 16, notes), "");
  EXPECT_TRUE(notes.empty());
  std::string crlf;
  for (char c : text) crlf += c == '\n' ? std::string("\r\n") : std::string(1, c);
  EXPECT_EQ(stl_check(tris, crlf, 16, notes), "");
}

// Issue 20, kind 10 (../shared/cases/render/r10_ascii_upper.stl): writers emit the keywords in upper case
// (`SOLID ... FACET NORMAL ... OUTER LOOP ... VERTEX ... ENDSOLID`) or mixed; the bytes are ASCII STL all the
// same (they do not add up to the binary size their header would announce) and read as the same cube.
TEST(MeshReadersStl, AsciiKeywordsInAnyCase) {
  const std::vector<Triangle> tris = cube_triangles();
  const std::string lower = ascii_solid("part", tris, 0, tris.size());
  std::string upper, mixed;
  for (size_t i = 0; i < lower.size(); ++i) {
    const char c = lower[i];
    upper += c >= 'a' && c <= 'z' ? char(c - 'a' + 'A') : c;
    mixed += c >= 'a' && c <= 'z' && i % 2 ? char(c - 'a' + 'A') : c;
  }
  std::vector<std::string> notes;
  EXPECT_EQ(stl_check(tris, upper, 8, notes), "");
  EXPECT_EQ(stl_check(tris, mixed, 8, notes), "");
  EXPECT_EQ(stl_check(tris, binary_stl(tris), 8, notes), "");
  EXPECT_TRUE(notes.empty());
}

TEST(MeshReadersStl, BinaryCubeHas8Positions) {
  const std::vector<Triangle> tris = cube_triangles();
  std::vector<std::string> notes;
  EXPECT_EQ(stl_check(tris, binary_stl(tris), 8, notes), "");
  EXPECT_TRUE(notes.empty());
  // -0 and +0 are one position.
  std::vector<Triangle> signed_zero = tris;
  for (auto& t : signed_zero)
    for (auto& p : t)
      if (p.x == 0.0f && (&t - signed_zero.data()) % 2) p.x = -0.0f;
  EXPECT_EQ(stl_check(signed_zero, binary_stl(signed_zero), 8, notes), "");
}

TEST(MeshReadersStl, BinaryWhoseHeaderStartsWithSolid) {
  const std::vector<Triangle> tris = cube_triangles();
  std::vector<std::string> notes;
  for (const char* header : {"solid", "solid cube", "solid cube\nfacet normal", "  solid\n\nendsolid"}) {
    EXPECT_EQ(stl_check(tris, binary_stl(tris, header), 8, notes), "") << header;
    EXPECT_TRUE(notes.empty());
  }
}

TEST(MeshReadersStl, BinaryWithTrailingBytesIsReadWithANote) {
  const std::vector<Triangle> tris = cube_triangles();
  for (const char* header : {"binary", "solid cube"})
    for (size_t trailing : {1, 7, 49, 50, 51, 1000}) {
      std::vector<std::string> notes;
      EXPECT_EQ(stl_check(tris, binary_stl(tris, header, trailing), 8, notes), "")
          << header << " + " << trailing;
      ASSERT_EQ(notes.size(), 1u) << header << " + " << trailing;
      expect_message(notes[0], "t.stl", {fmt::format("ignored {} bytes after the 12 triangles", trailing)});
    }
}

TEST(MeshReadersStl, BinaryShorterThanItsHeaderAnnounces) {
  const std::vector<Triangle> tris = cube_triangles();
  for (const char* header : {"binary", "solid cube"})
    for (int64_t announced : {int64_t(13), int64_t(100), int64_t(4000000000)}) {
      std::vector<std::string> notes;
      const std::string bytes = binary_stl(tris, header, 0, announced);
      const std::string message = error_of([&] { return read_stl("bad.stl", bytes, notes); });
      expect_message(message, "bad.stl",
                     {fmt::format("announces {} triangles ({} bytes) but the file has {} bytes", announced,
                                  84 + 50 * announced, bytes.size())},
                     header);
    }
  std::vector<std::string> notes;
  expect_message(error_of([&] { return read_stl("bad.stl", binary_stl(tris).substr(0, 83), notes); }),
                 "bad.stl", {"shorter than the 84-byte header"});
}

TEST(MeshReadersStl, ErrorsNameTheLineOrTriangle) {
  auto stl_error = [](const std::string& bytes) {
    std::vector<std::string> notes;
    return error_of([&] { return read_stl("bad.stl", bytes, notes); });
  };
  const std::string facet = "facet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\n";
  expect_message(stl_error("solid s\n" + facet + "vertex 0 nan 0\nendloop\nendfacet\nendsolid s\n"),
                 "bad.stl", {"line 6: vertex coordinate 'nan' is not a finite number"});
  expect_message(stl_error("solid s\n" + facet + "vertex 0 1\nendloop\nendfacet\nendsolid s\n"), "bad.stl",
                 {"line 6: a vertex needs three coordinates"});
  expect_message(stl_error("solid s\n" + facet + "vertex 0 1 0\n"), "bad.stl",
                 {"the file ends inside the loop that starts on line 3"});
  std::string binary = binary_stl(cube_triangles());
  const float inf = std::numeric_limits<float>::infinity();
  std::memcpy(&binary[84 + 50 * 5 + 12 + 12 * 2 + 8], &inf, 4);
  expect_message(stl_error(binary), "bad.stl", {"triangle 5 corner 2 is not finite (0, 0, inf)"});
}

// ------------------------------------------------------------------------------------------------------
// End to end: files on disk through load_mesh.

TEST(MeshReadersLoadMesh, EveryFormatEndToEnd) {
  test::TempDir dir;
  const Mesh m = simple_mesh();
  auto expect_soup = [&](const std::string& file, size_t vertices, size_t triangles,
                         std::vector<std::string>* warnings = nullptr) {
    try {
      TriangleSoup soup = load_mesh(dir.path() / file, warnings);
      EXPECT_EQ(soup.vertex_count(), vertices) << file;
      EXPECT_EQ(soup.triangle_count(), triangles) << file;
      return soup;
    } catch (const Error& e) {
      ADD_FAILURE() << file << ": " << e.what();
      return TriangleSoup();
    }
  };
  for (PlyFormat f : kPlyFormats) {
    const std::string file = fmt::format("mesh_{}.ply", format_name(f));
    dir.write(file, write_ply(f, {vertex_element(m, xyz(Ty::kF64)),
                                  face_element(m, {scalar("material_index", Ty::kI32),
                                                   list("vertex_indices", Ty::kU8, Ty::kI32)})})
                        .bytes);
    const TriangleSoup soup = expect_soup(file, 6, 6);
    for (size_t i = 0; i < soup.vertex_count() && i < m.positions.size(); ++i)
      EXPECT_EQ(glm::dvec3(glm::vec3(soup.positions[i])) + soup.anchor, glm::dvec3(glm::vec3(m.positions[i])))
          << file << " vertex " << i;
  }
  dir.write("mesh.obj", obj_text(m, Corner::kVVtVn, true));
  expect_soup("mesh.obj", 6, 6);
  dir.write("mesh.off", off_text(m, {Colour::kInt4, Colour::kFloat3, true, true, false}));
  expect_soup("mesh.off", 6, 6);
  std::vector<std::string> warnings;
  dir.write("cube.stl", binary_stl(cube_triangles(), "solid cube", 3));
  expect_soup("cube.stl", 8, 12, &warnings);
  ASSERT_EQ(warnings.size(), 1u);
  expect_message(warnings[0], (dir.path() / "cube.stl").string(), {"ignored 3 bytes"});
  // Errors carry the path.
  const std::string bad =
      write_ply(PlyFormat::kBig, {vertex_element(m, xyz(Ty::kF32)),
                                  face_element(m, {list("vertex_indices", Ty::kU8, Ty::kI32)})})
          .bytes;
  dir.write("short.ply", bad.substr(0, bad.size() - 2));
  expect_message(error_of([&] { return load_mesh(dir.path() / "short.ply"); }),
                 (dir.path() / "short.ply").string(),
                 {"face 4 of 5, property 'vertex_indices': the file ends here"});
}

}  // namespace
}  // namespace voxr
