// Mesh files through voxr's readers: a cube in every format, and every way a file can be wrong.
#include <gtest/gtest.h>

#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include "core/mesh_loader.h"
#include "core/mesh_topology.h"
#include "mesh/polygon_triangulation.h"
#include "test_support.h"
#include "util/error.h"

namespace voxr {
namespace {

namespace fs = std::filesystem;

// Unit cube [0,1]^3: 8 corners (x from bit 0, y bit 1, z bit 2), 6 outward quads.
const int kCubeQuads[6][4] = {{0, 4, 6, 2}, {1, 3, 7, 5}, {0, 1, 5, 4},
                              {2, 6, 7, 3}, {0, 2, 3, 1}, {4, 5, 7, 6}};
glm::vec3 corner(int i) {
  return glm::vec3(i & 1, (i >> 1) & 1, (i >> 2) & 1);
}

std::string cube_obj() {
  std::string s = "# unit cube\n";
  for (int i = 0; i < 8; ++i) s += fmt::format("v {} {} {}\n", corner(i).x, corner(i).y, corner(i).z);
  for (const auto& q : kCubeQuads)
    s += fmt::format("f {} {} {} {}\n", q[0] + 1, q[1] + 1, q[2] + 1, q[3] + 1);
  return s;
}

std::string cube_off() {
  std::string s = "OFF\n# unit cube\n8 6 12\n";
  for (int i = 0; i < 8; ++i) s += fmt::format("{} {} {}\n", corner(i).x, corner(i).y, corner(i).z);
  for (const auto& q : kCubeQuads) s += fmt::format("4 {} {} {} {}\n", q[0], q[1], q[2], q[3]);
  return s;
}

std::string cube_ply() {
  std::string s =
      "ply\nformat ascii 1.0\nelement vertex 8\nproperty float x\nproperty float y\nproperty float z\n"
      "element face 12\nproperty list uchar int vertex_indices\nend_header\n";
  for (int i = 0; i < 8; ++i) s += fmt::format("{} {} {}\n", corner(i).x, corner(i).y, corner(i).z);
  for (const auto& q : kCubeQuads)
    s += fmt::format("3 {} {} {}\n3 {} {} {}\n", q[0], q[1], q[2], q[0], q[2], q[3]);
  return s;
}

// Binary little-endian PLY with double coordinates and quads.
std::string cube_ply_binary() {
  std::string s =
      "ply\nformat binary_little_endian 1.0\ncomment unit cube\nelement vertex 8\nproperty double x\n"
      "property double y\nproperty double z\nelement face 6\nproperty list uchar int vertex_indices\n"
      "end_header\n";
  for (int i = 0; i < 8; ++i) {
    const double p[3] = {corner(i).x, corner(i).y, corner(i).z};
    s.append(reinterpret_cast<const char*>(p), sizeof p);
  }
  for (const auto& q : kCubeQuads) {
    s.push_back(4);
    s.append(reinterpret_cast<const char*>(q), 4 * sizeof(int));
  }
  return s;
}

std::string cube_stl_ascii() {
  std::string s = "solid cube\n";
  for (const auto& q : kCubeQuads)
    for (const auto& tri : {glm::ivec3(q[0], q[1], q[2]), glm::ivec3(q[0], q[2], q[3])}) {
      s += "facet normal 0 0 0\nouter loop\n";
      for (int c = 0; c < 3; ++c)
        s += fmt::format("vertex {} {} {}\n", corner(tri[c]).x, corner(tri[c]).y, corner(tri[c]).z);
      s += "endloop\nendfacet\n";
    }
  return s + "endsolid cube\n";
}

std::string cube_stl_binary() {
  std::string s(80, ' ');
  const uint32_t n = 12;
  s.append(reinterpret_cast<const char*>(&n), 4);
  for (const auto& q : kCubeQuads)
    for (const auto& tri : {glm::ivec3(q[0], q[1], q[2]), glm::ivec3(q[0], q[2], q[3])}) {
      float f[12] = {0, 0, 0};
      for (int c = 0; c < 3; ++c)
        for (int a = 0; a < 3; ++a) f[3 + 3 * c + a] = corner(tri[c])[a];
      s.append(reinterpret_cast<const char*>(f), sizeof f);
      s.append(2, '\0');
    }
  return s;
}

std::string load_error(const fs::path& file) {
  try {
    load_mesh(file);
  } catch (const Error& e) {
    return e.what();
  }
  return "no error";
}

// The message starts with the file path, then `reason`.
void expect_error(const fs::path& file, const std::string& reason) {
  const std::string message = load_error(file);
  EXPECT_EQ(message.rfind(file.string() + ": ", 0), 0u) << message;
  EXPECT_NE(message.find(reason), std::string::npos) << "message: " << message << "\nexpected: " << reason;
}

TEST(MeshLoader, LoadsCubeInEveryFormat) {
  test::TempDir dir;
  const std::map<std::string, std::string> files = {
      {"cube.obj", cube_obj()},          {"cube.off", cube_off()},       {"cube.ply", cube_ply()},
      {"binary.ply", cube_ply_binary()}, {"cube.stl", cube_stl_ascii()}, {"binary.stl", cube_stl_binary()},
      {"UPPER.OBJ", cube_obj()}};
  for (const auto& [name, content] : files) {
    SCOPED_TRACE(name);
    const TriangleSoup soup = load_mesh(dir.write(name, content));
    EXPECT_EQ(soup.triangle_count(), 12u);
    EXPECT_EQ(soup.vertex_count(), 8u);  // STL corners are merged
    EXPECT_TRUE(mesh_topology(soup).closed_and_oriented());
    EXPECT_NEAR(signed_volume(soup), 1.0, 1e-6);
    EXPECT_EQ(soup.bounds().lo, glm::vec3(0.0f));
    EXPECT_EQ(soup.bounds().hi, glm::vec3(1.0f));
    for (const glm::uvec4& t : soup.triangles) EXPECT_EQ(t.w, 0u);
  }
}

TEST(MeshLoader, FanTriangulatesPolygons) {
  test::TempDir dir;
  const TriangleSoup soup = load_mesh(
      dir.write("hex.obj", "v 0 0 0\nv 1 0 0\nv 2 1 0\nv 1 2 0\nv 0 2 0\nv -1 1 0\nf 1 2 3 4 5 6\n"));
  ASSERT_EQ(soup.triangle_count(), 4u);
  for (uint32_t k = 0; k < 4; ++k) EXPECT_EQ(soup.triangles[k], glm::uvec4(0, k + 1, k + 2, 0));
}

TEST(MeshLoader, ReadsOffVariants) {
  test::TempDir dir;
  // Counts on the keyword line, comments, a signed number, per-vertex and per-face colours (COFF).
  const TriangleSoup soup = load_mesh(
      dir.write("variant.off",
                "COFF 4 2 0 # counts here\n# comment\n0 0 0 1 0 0 1\n+1 0 0 1 0 0 1\n\n0 1 0 1 0 0 1\n"
                "1e0 1 0 1 0 0 1\n3 0 1 2 0.5 0.5 0.5\n3 1 3 2\n"));
  ASSERT_EQ(soup.triangle_count(), 2u);
  EXPECT_EQ(soup.positions[1], glm::vec4(1, 0, 0, 1));
  EXPECT_EQ(soup.triangles[1], glm::uvec4(1, 3, 2, 0));
}

TEST(MeshLoader, ReportsMissingUnreadableAndUnsupportedFiles) {
  test::TempDir dir;
  expect_error(dir.path() / "missing.obj", "no such file");
  fs::create_directory(dir.path() / "folder.obj");
  expect_error(dir.path() / "folder.obj", "is a directory");
  expect_error(dir.write("mesh.3ds", "x"), "unsupported mesh format '.3ds' (supported: ");
  expect_error(dir.write("noext", "x"), "unsupported mesh format ''");
  expect_error(dir.write("empty.obj", ""), "the file is empty");
  if (getuid() != 0) {  // root reads anything
    const fs::path locked = dir.write("locked.obj", cube_obj());
    fs::permissions(locked, fs::perms::none);
    expect_error(locked, "cannot open the file for reading");
  }
}

TEST(MeshLoader, RejectsGarbageInEveryFormat) {
  test::TempDir dir;
  std::string garbage;
  uint32_t x = 12345;
  for (int i = 0; i < 4000; ++i) {
    x = x * 1664525u + 1013904223u;
    garbage.push_back(char(x >> 24));
  }
  expect_error(dir.write("garbage.obj", garbage), "no triangles found");
  expect_error(dir.write("garbage.off", garbage), "an OFF file starts with the keyword OFF");
  expect_error(dir.write("garbage.ply", garbage), "a PLY file starts with the line 'ply'");
  expect_error(dir.write("garbage.stl", garbage), "binary STL header announces");
  expect_error(dir.write("prose.obj", "This is not a mesh.\nJust words.\n"), "no triangles found");
  expect_error(dir.write("points.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n"), "no triangles found");
  expect_error(dir.write("bad.off", "OFF\n3 1 0\n0 0 0\n1 0 zero\n0 1 0\n3 0 1 2\n"),
               "line 4: 'zero' is not a finite number");
}

TEST(MeshLoader, RejectsNonFiniteVertices) {
  test::TempDir dir;
  expect_error(dir.write("nan.obj", "v 0 0 0\nv nan 0 0\nv 0 1 0\nf 1 2 3\n"),
               "line 2: vertex coordinate 'nan' is not a finite number");
  expect_error(dir.write("inf.obj", "v 0 0 0\nv 1 0 0\nv 0 1 -inf\nf 1 2 3\n"),
               "line 3: vertex coordinate '-inf' is not a finite number");
  expect_error(dir.write("nan.off", "OFF\n3 1 0\n0 0 0\nnan 0 0\n0 1 0\n3 0 1 2\n"),
               "line 4: 'nan' is not a finite number");
  expect_error(dir.write("huge.off", "OFF\n3 1 0\n0 0 0\n1e39 0 0\n0 1 0\n3 0 1 2\n"),
               "line 4: '1e39' is not a finite number");  // beyond float
  expect_error(
      dir.write("nan.ply",
                "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
                "0 0 0\n1 0 nan\n0 1 0\n3 0 1 2\n"),
      "line 11: vertex 1 of 3, property 'z': nan is not a finite coordinate");
  expect_error(dir.write("nan.stl",
                         "solid s\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\n"
                         "vertex 0 NaN 0\nendloop\nendfacet\nendsolid s\n"),
               "line 6: vertex coordinate 'NaN' is not a finite number");
  // Binary files: NaN bit patterns.
  std::string stl = cube_stl_binary();
  const float nan = std::nanf("");
  std::memcpy(&stl[84 + 50 + 12 + 4], &nan, 4);
  expect_error(dir.write("nan.stl", stl), "triangle 1 corner 0 is not finite (0, nan, 0)");
  std::string ply = cube_ply_binary();
  const double inf = std::numeric_limits<double>::infinity();
  std::memcpy(&ply[ply.find("end_header\n") + 11 + 24 * 3 + 16], &inf, 8);
  expect_error(dir.write("inf.ply", ply), "vertex 3 of 8, property 'z': inf is not a finite coordinate");
}

TEST(MeshLoader, RejectsBadIndicesAndTruncatedFiles) {
  test::TempDir dir;
  expect_error(dir.write("index.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n"),
               "line 4: face corner '9' refers to vertex 9 but 3 vertices are defined before it");
  expect_error(dir.write("index.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n"),
               "line 6: face 0 uses vertex '3' but the file has 3 vertices");
  expect_error(dir.write("short.off", "OFF\n8 6 0\n0 0 0\n1 0 0\n"), "declares 8 vertices but ends after 2");
  expect_error(dir.write("counts.off", "OFF\n3 1\n"),
               "the OFF header ends before the vertex, face and edge counts");
  const std::string ply = cube_ply();
  expect_error(dir.write("short.ply", ply.substr(0, ply.size() - 30)),
               "line 26: face 8 of 12, property 'vertex_indices': the file ends here");
  expect_error(dir.write("header.ply", "ply\nformat ascii 1.0\nelement vertex 3\n"), "no end_header line");
  const std::string binary = cube_ply_binary();
  expect_error(dir.write("short_binary.ply", binary.substr(0, binary.size() - 3)),
               "face 5 of 6, property 'vertex_indices': the file ends here");
  expect_error(dir.write("shorter_binary.ply", binary.substr(0, binary.size() - 100)),
               "face 0 of 6, property 'vertex_indices': the file ends here");
  expect_error(
      dir.write("type.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty float128 x\nend_header\n1\n"),
      "line 4: element 'vertex' property 'x' has unknown PLY type 'float128'");
  expect_error(dir.write("binary.off", "OFF BINARY\n"), "line 1: binary OFF is not supported");
  expect_error(dir.write("4d.off", "4OFF\n1 0 0\n0 0 0 0\n"), "line 1: '4OFF' files are not supported");
}

TEST(MeshLoader, PrintsNothing) {
  test::TempDir dir;
  ::testing::internal::CaptureStderr();
  ::testing::internal::CaptureStdout();
  load_error(dir.write("index.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n"));
  load_error(dir.write("bad.ply", "ply\nformat binary_little_endian 1.0\nelement vertex 3\nend_header\nxx"));
  load_error(dir.write("bin.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2 0.5 0.5\n"));
  load_error(dir.write("mtl.obj", "mtllib missing.mtl\nusemtl x\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"));
  const std::string err = ::testing::internal::GetCapturedStderr();
  const std::string out = ::testing::internal::GetCapturedStdout();
  EXPECT_EQ(err, "");
  EXPECT_EQ(out, "");
}

// Two triangles over four vertices, written with every separator, line ending and comment placement the OFF
// reader accepts; all read as the plain file does.
TEST(MeshLoader, ReadsOffSeparatorsLineEndingsAndComments) {
  test::TempDir dir;
  const std::string plain = "OFF\n4 2 0\n0 0 0\n1 0 0\n0 1 0\n1 1 0.5\n3 0 1 2\n3 1 3 2\n";
  const TriangleSoup expected = load_mesh(dir.write("plain.off", plain));
  ASSERT_EQ(expected.triangle_count(), 2u);
  const std::map<std::string, std::string> variants = {
      {"crlf", "OFF\r\n4 2 0\r\n0 0 0\r\n1 0 0\r\n0 1 0\r\n1 1 0.5\r\n3 0 1 2\r\n3 1 3 2\r\n"},
      {"tabs", "OFF\t4\t2\t0\n\t0\t0 0\n1\v0\f0\n0\r1 0\n1 1 0.5 \t\n3\t0\t1\t2\n 3 1 3 2\t\n"},
      {"comments",
       "# head\nOFF # keyword\n# counts next\n4 2 0 #\n0 0 0#no space\n1 0 0\n#\n0 1 0\n"
       "\n   \n1 1 0.5 # last vertex\n# faces\n3 0 1 2#\n\n# between faces\n3 1 3 2 # end\n# tail"},
      {"no final newline", "OFF\n4 2 0\n0 0 0\n1 0 0\n0 1 0\n1 1 0.5\n3 0 1 2\n3 1 3 2"},
      {"crlf, no final newline",
       "OFF\r\n4 2 0\r\n0 0 0\r\n1 0 0\r\n0 1 0\r\n1 1 0.5\r\n3 0 1 2\r\n3 1 3 2\r"},
      {"trailing numbers", "OFF\n4 2 0\n0 0 0\n1 0 0\n0 1 0\n1 1 0.5\n3 0 1 2\n3 1 3 2\n\n1 2.5 -3\n# c\n7"},
      {"counts apart", "OFF\n4\n2\n\n0\n0 0 0\n1 0 0\n0 1 0\n1 1 0.5\n3 0 1 2\n3 1 3 2\n"},
      {"number forms", "OFF 4 2 0\n+0 -0 0.0\n1. +0e0 0e5\n.0 1 0\n1E0 0.1e1 5e-1\n3 0 1 2\n3 1 3 2\n"},
      // Index tokens of ten digits or more, which are still the same indices.
      {"long indices",
       "OFF\n4 2 0\n0 0 0\n1 0 0\n0 1 0\n1 1 0.5\n3 0000000000 01 00000000000002\n"
       "0000000000000000003 1 3 2\n"},
  };
  for (const auto& [what, content] : variants) {
    SCOPED_TRACE(what);
    const TriangleSoup soup = load_mesh(dir.write("variant.off", content));
    EXPECT_EQ(soup.positions, expected.positions);
    EXPECT_EQ(soup.triangles, expected.triangles);
  }
}

// Every coordinate reads as the float nearest to the decimal's nearest double, whatever its form, in a file
// large enough for the fast path to carry it (with colours, polygons and comments along the way).
TEST(MeshLoader, ReadsOffNumbersExactly) {
  test::TempDir dir;
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> value(-1000.0, 1000.0);
  std::uniform_int_distribution<int> form(0, 5);
  const size_t vertices = 3000, faces = 2000;
  std::string s = fmt::format("OFF\n{} {} 0\n", vertices, faces);
  HostArray<glm::vec4> expected(vertices);
  PolygonMesh polygons;  // the faces as written, triangulated below as load_mesh must
  for (size_t v = 0; v < vertices; ++v) {
    glm::dvec3& exact = polygons.positions.emplace_back();
    for (int c = 0; c < 3; ++c) {
      const double x = value(rng) * std::pow(10.0, double(int(rng() % 20) - 10));
      std::string token;
      switch (form(rng)) {
        case 0:
          token = fmt::format("{}", x);
          break;
        case 1:
          token = fmt::format("{:.9g}", x);
          break;
        case 2:
          token = fmt::format("{:e}", x);
          break;
        case 3:
          token = fmt::format("{:.20f}", x);
          break;
        case 4:
          token = fmt::format("{:.3f}", x);
          break;
        default:
          token = fmt::format("{}{:.17g}", x >= 0 ? "+" : "", x);
          break;
      }
      s += token + (c < 2 ? " " : "");
      exact[c] = std::strtod(token.c_str(), nullptr);
    }
    s += v % 7 == 0 ? " 0.5 0.5 0.5 1\n" : v % 11 == 0 ? " # comment\n" : "\n";
  }
  for (size_t f = 0; f < faces; ++f) {
    const uint32_t n = 3 + uint32_t(f % 3);
    std::vector<uint32_t> ids(n);
    for (uint32_t& id : ids) id = uint32_t(rng() % vertices);
    s += std::to_string(n);
    for (uint32_t id : ids) s += fmt::format(" {}", id);
    s += f % 5 == 0 ? " 255 0 0\r\n" : "\n";
    polygons.add_face(ids.data(), n);
  }
  HostArray<glm::uvec4> triangles;
  TriangulationReport report;
  triangulate(polygons, triangles, report);
  const TriangleSoup soup = load_mesh(dir.write("numbers.off", s));
  // Positions are the file's numbers relative to the anchor, rounded to float once.
  for (size_t v = 0; v < vertices; ++v)
    expected[v] = glm::vec4(glm::vec3(polygons.positions[v] - soup.anchor), 1.0f);
  ASSERT_EQ(soup.positions.size(), expected.size());
  for (size_t v = 0; v < vertices; ++v)
    ASSERT_EQ(std::memcmp(&soup.positions[v], &expected[v], sizeof expected[v]), 0) << "vertex " << v;
  EXPECT_EQ(soup.triangles, triangles);
}

TEST(MeshLoader, OffErrorsNameTheLine) {
  test::TempDir dir;
  const std::string head = "OFF\n3 1 0\n0 0 0\n1 0 0\n";  // line 5 is the third vertex, line 6 the face
  expect_error(dir.write("a.off", head + "0 1.5x 0\n3 0 1 2\n"), "line 5: '1.5x' is not a finite number");
  expect_error(dir.write("b.off", head + "0 1e 0\n3 0 1 2\n"), "line 5: '1e' is not a finite number");
  expect_error(dir.write("c.off", head + "0 1 0x1\n3 0 1 2\n"), "line 5: '0x1' is not a finite number");
  expect_error(dir.write("d.off", head + "0 1\n3 0 1 2\n"), "line 5: vertex 2 needs three coordinates");
  expect_error(dir.write("e.off", head + "0 1 0 nan\n3 0 1 2\n"), "line 5: 'nan' is not a finite number");
  expect_error(dir.write("f.off", head + "0 1 0\r\n3 0 1\r\n"), "line 6: face 0 lists fewer than 3 vertices");
  expect_error(dir.write("g.off", head + "0 1 0\n3 0 1 4294967296\n"),
               "line 6: face 0 uses vertex '4294967296' but the file has 3 vertices");
  expect_error(dir.write("h.off", head + "0 1 0\n3 0 1 -2\n"),
               "line 6: face 0 uses vertex '-2' but the file has 3 vertices");
  expect_error(dir.write("i.off", head + "0 1 0\n3 0 1 +2\n"),
               "line 6: face 0 uses vertex '+2' but the file has 3 vertices");
  expect_error(dir.write("j.off", head + "0 1 0\n3.0 0 1 2\n"),
               "line 6: the face vertex count '3.0' is not a non-negative integer");
  expect_error(dir.write("k.off", head + "0 1 0\n18446744073709551615 0 1 2\n"),
               "line 6: the face vertex count '18446744073709551615' is not a non-negative integer");
  expect_error(dir.write("l.off", head + "0 1 0\n3 0 1 2 red\n"), "line 6: 'red' is not a finite number");
  expect_error(dir.write("m.off", head + "0 1 0\n3 0 1 2\n\n# fine\n1 2\n1 x"),
               "line 10: 'x' is not a finite number");
  expect_error(dir.write("n.off", head + "0 1 0\n# no face\n\n"), "declares 1 faces but ends after 0");
  expect_error(dir.write("o.off", "OFF\r\n3 1 0\r\n0 0 0\r\n\r\n1 0 0 # c\r\n0 1 +\r\n3 0 1 2\r\n"),
               "line 6: '+' is not a finite number");
  EXPECT_EQ(load_error(dir.write("p.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2 0.5 0.5 0.5 1 1")),
            "no error");
}

// Files of a megabyte and more are read by two threads (vertices, faces): the same soup, and the error of the
// earliest line when both halves have one.
TEST(MeshLoader, ReadsLargeOffFilesLikeSmallOnes) {
  test::TempDir dir;
  const uint32_t n = 120;  // (n + 1)^2 vertices, 2 n^2 triangles: about 1.3 MB below
  std::vector<std::string> lines = {"OFF", "# a sheet", fmt::format("{} {} 0", (n + 1) * (n + 1), n * n)};
  TriangleSoup expected;
  for (uint32_t j = 0; j <= n; ++j)
    for (uint32_t i = 0; i <= n; ++i) {
      const glm::vec4 p(float(i) * 0.1f, float(j) * 0.3f, float(i * j) * 1e-3f, 1.0f);
      lines.push_back(fmt::format("{} {} {} 0.25 0.5 0.75 1", p.x, p.y, p.z));
      if (i == 7) lines.push_back("# between vertices");
      expected.positions.push_back(p);
    }
  const size_t first_face = lines.size();  // index into `lines`: line first_face + 1 of the file
  for (uint32_t j = 0; j < n; ++j)
    for (uint32_t i = 0; i < n; ++i) {
      const uint32_t a = j * (n + 1) + i, b = a + 1, c = a + n + 2, d = a + n + 1;
      lines.push_back(fmt::format("4 {} {} {} {} 255 255 255 255\r", a, b, c, d));
      if (i == 5) lines.push_back("");
      expected.triangles.push_back({a, b, c, 0});
      expected.triangles.push_back({a, c, d, 0});
    }
  lines.push_back("1 2 3 # tail");
  auto join = [](const std::vector<std::string>& l) {
    std::string s;
    for (const std::string& line : l) s += line + "\n";
    return s;
  };
  ASSERT_GT(join(lines).size(), size_t(1) << 20);
  const TriangleSoup soup = load_mesh(dir.write("large.off", join(lines)));
  EXPECT_EQ(soup.positions, expected.positions);
  EXPECT_EQ(soup.triangles, expected.triangles);

  std::vector<std::string> bad = lines;
  bad[first_face + 1000] = "4 1 2 3 x";
  expect_error(dir.write("face.off", join(bad)),
               fmt::format("line {}: 'x' is not a finite number", first_face + 1001));
  bad[100] = "1 2";
  expect_error(dir.write("both.off", join(bad)), "line 101: vertex 96 needs three coordinates");
  bad = lines;
  bad.back() = "1 2 three";
  expect_error(dir.write("tail.off", join(bad)),
               fmt::format("line {}: 'three' is not a finite number", lines.size()));
  bad.back() = "";
  bad[first_face + 3] = "4 1 2 3 99999999";
  expect_error(dir.write("index.off", join(bad)),
               fmt::format("line {}: face 3 uses vertex '99999999' but the file has", first_face + 4));
  bad = lines;
  bad.resize(lines.size() - 10);
  expect_error(dir.write("short.off", join(bad)), "faces but ends after");
}

// A named pipe cannot be mapped: it is read instead.
TEST(MeshLoader, ReadsOffFromAPipe) {
  test::TempDir dir;
  const fs::path fifo = dir.path() / "pipe.off";
  ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
  // Blank lines between the header and the vertices: more than one read.
  const std::string content = "OFF\n3 1 0\n" + std::string(200000, '\n') + "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
  std::thread writer([&] { std::ofstream(fifo, std::ios::binary) << content; });
  TriangleSoup soup;
  std::string error;
  try {
    soup = load_mesh(fifo);
  } catch (const Error& e) {
    error = e.what();
    std::ifstream drain(fifo);  // lets the writer finish if the pipe was never opened
    drain.ignore(std::numeric_limits<std::streamsize>::max());
  }
  writer.join();
  EXPECT_EQ(error, "");
  ASSERT_EQ(soup.triangle_count(), 1u);
  EXPECT_EQ(soup.positions[1], glm::vec4(1, 0, 0, 1));
}

// Meshes fetched by scripts/fetch-meshes.sh into $VOXR_MESH_DIR (default: data/meshes in the source tree).
fs::path mesh_dir() {
  const char* env = std::getenv("VOXR_MESH_DIR");
  return env && *env ? fs::path(env) : fs::path(VOXR_SOURCE_DIR) / "data" / "meshes";
}

void expect_packaged_mesh(const std::string& name, size_t triangles) {
  const fs::path file = mesh_dir() / name;
  if (!fs::exists(file)) GTEST_SKIP() << file << " is absent; run scripts/fetch-meshes.sh to fetch it";
  const TriangleSoup soup = load_mesh(file);
  EXPECT_EQ(soup.triangle_count(), triangles) << name;
  EXPECT_EQ(validate_soup(soup, name), 0u) << name << ": degenerate triangles";
  EXPECT_FALSE(soup.bounds().empty());
}

TEST(MeshLoader, PackagedBunny) {
  expect_packaged_mesh("bunny.obj", 69666);
}
TEST(MeshLoader, PackagedArmadillo) {
  expect_packaged_mesh("armadillo.off", 52000);
}
TEST(MeshLoader, PackagedBunny00) {
  expect_packaged_mesh("bunny00.off", 75408);
}
TEST(MeshLoader, PackagedChineseDragon) {
  expect_packaged_mesh("ChineseDragon-10kv.off", 19994);
}
TEST(MeshLoader, PackagedElephant) {
  expect_packaged_mesh("refined_elephant.off", 88928);
}
TEST(MeshLoader, PackagedShark) {
  expect_packaged_mesh("mech-holes-shark.off", 10192);
}

}  // namespace
}  // namespace voxr
