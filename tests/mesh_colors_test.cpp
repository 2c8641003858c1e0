// Surface colour from mesh files into the soup (triangle_soup.h SoupColors): each format writes a tiny
// coloured or textured file and the soup's arrays are compared exactly; append, validate_soup, the triangle
// splitter, subdivision and duplicate removal keep them; every fault gives its one-line message.
#include <gtest/gtest.h>

#include <stb_image_write.h>

#include <cstring>
#include <string>
#include <vector>

#include "core/mesh_loader.h"
#include "core/mesh_topology.h"
#include "core/scene.h"
#include "core/subdivide.h"
#include "mesh/texture_reader.h"
#include "test_support.h"
#include "util/error.h"
#include "voxelize/triangle_splitter.h"

namespace voxr {
namespace {

namespace fs = std::filesystem;
using test::TempDir;

constexpr uint32_t rgba(uint32_t r, uint32_t g, uint32_t b, uint32_t a = 255) {
  return r | g << 8 | b << 16 | a << 24;
}
constexpr uint32_t kWhite = 0xffffffffu;

template <typename A>
std::vector<typename A::value_type> vec(const A& a) {
  return std::vector<typename A::value_type>(a.begin(), a.end());
}

// The message of the voxr::Error that `f` throws ("" when it throws none).
template <typename F>
std::string error_of(F&& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

// A message that is one line and starts with `file`.
void expect_one_line(const std::string& message, const std::string& file) {
  EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  EXPECT_EQ(message.rfind(file, 0), 0u) << message;
}

// 2 x 2 RGBA texels of the test textures, row 0 at the top.
const uint32_t kTexels[4] = {rgba(255, 0, 0, 255), rgba(0, 255, 0, 200), rgba(0, 0, 255, 100),
                             rgba(10, 20, 30, 40)};

fs::path write_png(const TempDir& dir, const std::string& name) {
  const fs::path p = dir.path() / name;
  EXPECT_TRUE(stbi_write_png(p.c_str(), 2, 2, 4, kTexels, 8));
  return p;
}

std::string file_text(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

std::string base64(const std::string& bytes) {
  static const char* k = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  for (size_t i = 0; i < bytes.size(); i += 3) {
    uint32_t v = uint32_t(uint8_t(bytes[i])) << 16;
    if (i + 1 < bytes.size()) v |= uint32_t(uint8_t(bytes[i + 1])) << 8;
    if (i + 2 < bytes.size()) v |= uint32_t(uint8_t(bytes[i + 2]));
    out += k[(v >> 18) & 63];
    out += k[(v >> 12) & 63];
    out += i + 1 < bytes.size() ? k[(v >> 6) & 63] : '=';
    out += i + 2 < bytes.size() ? k[v & 63] : '=';
  }
  return out;
}

// ---- textures ----

TEST(TextureReader, DecodesPngTgaBmpToRgba8) {
  TempDir dir;
  const SoupTexture png = read_texture(write_png(dir, "t.png"), "mesh.obj");
  EXPECT_EQ(png.width, 2u);
  EXPECT_EQ(png.height, 2u);
  EXPECT_EQ(png.texels, std::vector<uint32_t>(kTexels, kTexels + 4));
  // RGB and grey are expanded with alpha 255.
  const uint8_t rgb[12] = {1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12};
  const std::vector<uint32_t> rgb_texels = {rgba(1, 2, 3), rgba(4, 5, 6), rgba(7, 8, 9), rgba(10, 11, 12)};
  for (const char* ext : {"png", "tga", "bmp"}) {
    SCOPED_TRACE(ext);
    const fs::path p = dir.path() / (std::string("rgb.") + ext);
    const std::string e = ext;
    ASSERT_TRUE(e == "png"   ? stbi_write_png(p.c_str(), 2, 2, 3, rgb, 6)
                : e == "tga" ? stbi_write_tga(p.c_str(), 2, 2, 3, rgb)
                             : stbi_write_bmp(p.c_str(), 2, 2, 3, rgb));
    EXPECT_EQ(read_texture(p, "m").texels, rgb_texels);
  }
  const uint8_t grey[4] = {0, 50, 100, 250};
  const fs::path g = dir.path() / "grey.png";
  ASSERT_TRUE(stbi_write_png(g.c_str(), 2, 2, 1, grey, 2));
  EXPECT_EQ(read_texture(g, "m").texels, (std::vector<uint32_t>{rgba(0, 0, 0), rgba(50, 50, 50),
                                                                rgba(100, 100, 100), rgba(250, 250, 250)}));
  const fs::path j = dir.path() / "t.jpg";
  ASSERT_TRUE(stbi_write_jpg(j.c_str(), 2, 2, 3, rgb, 90));
  const SoupTexture jpeg = read_texture(j, "m");
  EXPECT_EQ(jpeg.width * jpeg.height, 4u);
}

TEST(TextureReader, RefusesBadFilesInOneLine) {
  TempDir dir;
  std::string m = error_of([&] { read_texture(dir.path() / "missing.png", "mesh.mtl", 7); });
  expect_one_line(m, "mesh.mtl: line 7: texture");
  EXPECT_NE(m.find("missing.png"), std::string::npos) << m;
  m = error_of([&] { read_texture(dir.write("junk.png", "not an image at all"), "m.obj"); });
  expect_one_line(m, "m.obj: texture");
  EXPECT_NE(m.find("not a texture image"), std::string::npos) << m;
  m = error_of([&] { decode_texture("e.png", ""); });
  expect_one_line(m, "e.png");
  // A PNG header claiming 8000 x 9000 texels in a 75-byte file is refused before decoding.
  std::string png = file_text(write_png(dir, "big.png"));
  const unsigned char size[8] = {0, 0, 0x1f, 0x40, 0, 0, 0x23, 0x28};
  std::memcpy(png.data() + 16, size, 8);
  m = error_of([&] { decode_texture("big.png", png); });
  expect_one_line(m, "big.png");
  EXPECT_NE(m.find("more than voxr reads"), std::string::npos) << m;
  const unsigned char medium[8] = {0, 0, 0x10, 0, 0, 0, 0x10, 0};  // 4096 x 4096 in 75 bytes
  std::memcpy(png.data() + 16, medium, 8);
  m = error_of([&] { decode_texture("lie.png", png); });
  EXPECT_NE(m.find("the file has only"), std::string::npos) << m;
}

// ---- PLY ----

TEST(MeshColors, PlyAsciiVertexAndFaceColours) {
  TempDir dir;
  const fs::path p =
      dir.write("c.ply",
                "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
                "property float z\nproperty uchar red\nproperty uchar green\nproperty uchar blue\n"
                "element face 2\nproperty list uchar int vertex_indices\nproperty uchar red\n"
                "property uchar green\nproperty uchar blue\nend_header\n"
                "0 0 0 255 0 0\n1 0 0 0 255 0\n0 1 0 0 0 255\n1 1 0 10 20 30\n"
                "3 0 1 2 200 100 50\n4 0 1 3 2 1 2 3\n");
  const TriangleSoup soup = load_mesh(p);
  const SoupColors& c = soup.colors;
  EXPECT_EQ(vec(c.vertex_rgba),
            (std::vector<uint32_t>{rgba(255, 0, 0), rgba(0, 255, 0), rgba(0, 0, 255), rgba(10, 20, 30)}));
  EXPECT_TRUE(c.vertex_uv.empty());
  ASSERT_EQ(soup.triangle_count(), 3u);
  EXPECT_EQ(vec(c.triangle_look), (std::vector<uint32_t>{0, 1, 1}));
  ASSERT_EQ(c.looks.size(), 2u);
  EXPECT_EQ(c.looks[0].factor_rgba, rgba(200, 100, 50));
  EXPECT_EQ(c.looks[1].factor_rgba, rgba(1, 2, 3));
  EXPECT_EQ(c.looks[0].texture, -1);
  EXPECT_EQ(validate_soup(soup, "c.ply"), 0u);
}

TEST(MeshColors, PlyBinaryFloatColoursWithAlpha) {
  std::string body;
  auto f32 = [&](float v) { body.append(reinterpret_cast<const char*>(&v), 4); };
  const float colours[3][4] = {{0, 0.5f, 1, 0.25f}, {1, 1, 1, 1}, {0.2f, 0.4f, 0.6f, 0.8f}};
  for (int v = 0; v < 3; ++v) {
    f32(float(v == 1));
    f32(float(v == 2));
    f32(0);
    for (float x : colours[v]) f32(x);
  }
  body += char(3);
  for (int32_t i : {0, 1, 2}) body.append(reinterpret_cast<const char*>(&i), 4);
  TempDir dir;
  const fs::path p =
      dir.write("b.ply",
                "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                "property float z\nproperty float red\nproperty float green\nproperty float blue\n"
                "property float alpha\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n" +
                    body);
  const TriangleSoup soup = load_mesh(p);
  EXPECT_EQ(vec(soup.colors.vertex_rgba),
            (std::vector<uint32_t>{rgba(0, 128, 255, 64), kWhite, rgba(51, 102, 153, 204)}));
  EXPECT_TRUE(soup.colors.looks.empty());
  EXPECT_TRUE(soup.colors.triangle_look.empty());
}

TEST(MeshColors, PlyColourOutOfRange) {
  TempDir dir;
  const std::string head =
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n";
  const fs::path a =
      dir.write("a.ply", head +
                             "property ushort red\nproperty uchar green\nproperty uchar blue\n"
                             "element face 1\nproperty list uchar int vertex_indices\nend_header\n"
                             "0 0 0 0 0 0\n1 0 0 300 0 0\n0 1 0 0 0 0\n3 0 1 2\n");
  std::string m = error_of([&] { load_mesh(a); });
  expect_one_line(m, a.string());
  EXPECT_NE(m.find("line 14: vertex 1 of 3, property 'red': colour value 300 is not in 0..255"),
            std::string::npos)
      << m;
  const fs::path b =
      dir.write("b.ply", head +
                             "property float red\nproperty float green\nproperty float blue\n"
                             "element face 1\nproperty list uchar int vertex_indices\nend_header\n"
                             "0 0 0 0 0 0\n1 0 0 0 1.5 0\n0 1 0 0 0 0\n3 0 1 2\n");
  m = error_of([&] { load_mesh(b); });
  expect_one_line(m, b.string());
  EXPECT_NE(m.find("property 'green': colour value 1.5 is not in [0, 1]"), std::string::npos) << m;
}

TEST(MeshColors, PlyTextureFileWithVertexAndCornerUvs) {
  TempDir dir;
  write_png(dir, "t.png");
  const std::string head =
      "ply\nformat ascii 1.0\ncomment TextureFile t.png\nelement vertex 4\nproperty float x\n"
      "property float y\nproperty float z\n";
  // Per vertex.
  TriangleSoup soup = load_mesh(dir.write(
      "v.ply",
      head + "property float s\nproperty float t\nelement face 1\nproperty list uchar int vertex_indices\n"
             "end_header\n0 0 0 0 0\n1 0 0 1 0\n0 1 0 0 1\n1 1 0 1 1\n3 0 1 2\n"));
  EXPECT_EQ(vec(soup.colors.vertex_uv), (std::vector<glm::vec2>{{0, 0}, {1, 0}, {0, 1}, {1, 1}}));
  ASSERT_EQ(soup.colors.looks.size(), 1u);
  EXPECT_EQ(soup.colors.looks[0].factor_rgba, kWhite);
  EXPECT_EQ(soup.colors.looks[0].texture, 0);
  ASSERT_EQ(soup.colors.textures.size(), 1u);
  EXPECT_EQ(soup.colors.textures[0].texels, std::vector<uint32_t>(kTexels, kTexels + 4));
  // Per corner (MeshLab's texcoord): vertex 1 carries two different UVs and is split.
  soup = load_mesh(dir.write("c.ply", head + "element face 2\nproperty list uchar int vertex_indices\n"
                                             "property list uchar float texcoord\nend_header\n"
                                             "0 0 0\n1 0 0\n0 1 0\n1 1 0\n"
                                             "3 0 1 2 6 0 0 0.5 0 0 1\n3 1 3 2 6 1 0 1 1 0 1\n"));
  EXPECT_EQ(vec(soup.triangles), (std::vector<glm::uvec4>{{0, 1, 2, 0}, {4, 3, 2, 0}}));
  EXPECT_EQ(vec(soup.colors.vertex_uv), (std::vector<glm::vec2>{{0, 0}, {0.5f, 0}, {0, 1}, {1, 1}, {1, 0}}));
  EXPECT_EQ(soup.positions[4], soup.positions[1]);
  EXPECT_EQ(validate_soup(soup, "c.ply"), 0u);
  // Errors: a missing texture names the header line; texcoord must pair with the corners.
  const fs::path missing = dir.write("m.ply",
                                     "ply\nformat ascii 1.0\ncomment TextureFile gone.png\n"
                                     "element vertex 3\nproperty float x\nproperty float y\n"
                                     "property float z\nelement face 1\n"
                                     "property list uchar int vertex_indices\nend_header\n"
                                     "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
  std::string m = error_of([&] { load_mesh(missing); });
  expect_one_line(m, missing.string() + ": line 3: texture");
  const fs::path odd = dir.write("o.ply", head +
                                              "element face 1\nproperty list uchar int vertex_indices\n"
                                              "property list uchar float texcoord\nend_header\n"
                                              "0 0 0\n1 0 0\n0 1 0\n1 1 0\n3 0 1 2 4 0 0 1 0\n");
  m = error_of([&] { load_mesh(odd); });
  expect_one_line(m, odd.string());
  EXPECT_NE(m.find("face 0 of 1, property 'texcoord': 2 texture coordinate pairs for 3 corners"),
            std::string::npos)
      << m;
}

// ---- OFF ----

TEST(MeshColors, CoffIntegerAndFloatColours) {
  TempDir dir;
  const fs::path a = dir.write("a.off",
                               "COFF\n3 1 0\n0 0 0 255 0 0 255\n1 0 0 0 255 0 128\n"
                               "0 1 0 0 0 255 0\n3 0 1 2\n");
  TriangleSoup soup = load_mesh(a);
  EXPECT_EQ(vec(soup.colors.vertex_rgba),
            (std::vector<uint32_t>{rgba(255, 0, 0, 255), rgba(0, 255, 0, 128), rgba(0, 0, 255, 0)}));
  EXPECT_TRUE(soup.colors.looks.empty());
  // Floats, 3 components, after a normal (CNOFF).
  const fs::path b = dir.write("b.off",
                               "CNOFF\n3 1 0\n0 0 0 0 0 1 1.0 0.5 0\n1 0 0 0 0 1 0 0 0.\n"
                               "0 1 0 0 0 1 1 1 1.0\n3 0 1 2\n");
  soup = load_mesh(b);
  EXPECT_EQ(vec(soup.colors.vertex_rgba), (std::vector<uint32_t>{rgba(255, 128, 0), rgba(0, 0, 0), kWhite}));
  // A vertex without colour columns is white.
  soup = load_mesh(dir.write("c.off", "COFF\n3 1 0\n0 0 0 0 0 255\n1 0 0\n0 1 0\n3 0 1 2\n"));
  EXPECT_EQ(vec(soup.colors.vertex_rgba), (std::vector<uint32_t>{rgba(0, 0, 255), kWhite, kWhite}));
}

TEST(MeshColors, OffFaceColoursBecomeLooks) {
  TempDir dir;
  const fs::path p = dir.write("f.off",
                               "OFF\n4 3 0\n0 0 0\n1 0 0\n0 1 0\n1 1 0\n3 0 1 2\n3 1 3 2 1.0 0 0\n"
                               "3 0 1 3 255 0 0 255\n");
  const TriangleSoup soup = load_mesh(p);
  EXPECT_TRUE(soup.colors.vertex_rgba.empty());
  ASSERT_EQ(soup.colors.looks.size(), 2u);
  EXPECT_EQ(soup.colors.looks[0].factor_rgba, kWhite);
  EXPECT_EQ(soup.colors.looks[1].factor_rgba, rgba(255, 0, 0));
  EXPECT_EQ(vec(soup.colors.triangle_look), (std::vector<uint32_t>{0, 1, 1}));
  // Without any face colour, nothing is allocated.
  const TriangleSoup plain = load_mesh(dir.write("p.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2 7\n"));
  EXPECT_TRUE(plain.colors.empty());
  EXPECT_TRUE(plain.colors.triangle_look.empty());
}

TEST(MeshColors, OffColourErrors) {
  TempDir dir;
  const fs::path a = dir.write("a.off", "COFF\n3 1 0\n0 0 0 255 0 0\n1 0 0 0 256 0\n0 1 0 0 0 0\n3 0 1 2\n");
  std::string m = error_of([&] { load_mesh(a); });
  expect_one_line(m, a.string());
  EXPECT_NE(m.find("line 4: vertex colour component '256' is not in 0..255"), std::string::npos) << m;
  const fs::path b = dir.write("b.off", "COFF\n3 1 0\n0 0 0 1 0\n1 0 0 0 1 0\n0 1 0 0 0 0\n3 0 1 2\n");
  m = error_of([&] { load_mesh(b); });
  expect_one_line(m, b.string());
  EXPECT_NE(m.find("line 3: vertex 0 has 2 colour components after column 3; a colour has 3 or 4"),
            std::string::npos)
      << m;
  const fs::path c = dir.write("c.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2 0.5 1.5 0\n");
  m = error_of([&] { load_mesh(c); });
  expect_one_line(m, c.string());
  EXPECT_NE(m.find("line 6: face colour component '1.5' is not in [0, 1]"), std::string::npos) << m;
}

// ---- OBJ + MTL + PNG ----

const char* kObj =
    "mtllib looks.mtl\n"
    "v 0 0 0 1 0 0\n"
    "v 1 0 0 0 1 0\n"
    "v 0 1 0 0 0 1\n"
    "v 1 1 0\n"
    "vt 0 0\nvt 1 0\nvt 0 1\nvt 0.5 0.5\n"
    "usemtl textured\n"
    "f 1/1 2/2 3/3\n"
    "usemtl plain\n"
    "f 2/4 4/4 3/4\n"
    "f 1 2 3\n";

TEST(MeshColors, ObjMtlTextureAndVertexColours) {
  TempDir dir;
  dir.write("looks.mtl",
            "newmtl textured\nKd 1 1 1\nmap_Kd tex dir/tex.png\n\nnewmtl plain\nKd 0.5 0.25 1\nd 0.5\n");
  fs::create_directories(dir.path() / "tex dir");
  write_png(dir, "tex dir/tex.png");
  const TriangleSoup soup = load_mesh(dir.write("m.obj", kObj));
  const SoupColors& c = soup.colors;
  // Vertices 2 and 3 carry two UVs each: copies 4 and 5 are appended for their second one; the corners of
  // the last face have no vt, unlike each vertex's first corner: copies 6, 7, 8 with UV (0, 0).
  ASSERT_EQ(soup.vertex_count(), 9u);
  EXPECT_EQ(soup.positions[4], soup.positions[1]);
  EXPECT_EQ(soup.positions[5], soup.positions[2]);
  EXPECT_EQ(vec(soup.triangles), (std::vector<glm::uvec4>{{0, 1, 2, 0}, {4, 3, 5, 1}, {6, 7, 8, 1}}));
  const uint32_t r = rgba(255, 0, 0), g = rgba(0, 255, 0), b = rgba(0, 0, 255);
  EXPECT_EQ(vec(c.vertex_rgba), (std::vector<uint32_t>{r, g, b, kWhite, g, b, r, g, b}));
  EXPECT_EQ(vec(c.vertex_uv),
            (std::vector<glm::vec2>{
                {0, 0}, {1, 0}, {0, 1}, {0.5f, 0.5f}, {0.5f, 0.5f}, {0.5f, 0.5f}, {0, 0}, {0, 0}, {0, 0}}));
  EXPECT_EQ(vec(c.triangle_look), (std::vector<uint32_t>{0, 1, 1}));
  ASSERT_EQ(c.looks.size(), 2u);
  EXPECT_EQ(c.looks[0].factor_rgba, kWhite);
  EXPECT_EQ(c.looks[0].texture, 0);
  EXPECT_EQ(c.looks[1].factor_rgba, rgba(128, 64, 255, 128));
  EXPECT_EQ(c.looks[1].texture, -1);
  ASSERT_EQ(c.textures.size(), 1u);
  EXPECT_EQ(c.textures[0].width, 2u);
  EXPECT_EQ(c.textures[0].texels, std::vector<uint32_t>(kTexels, kTexels + 4));
  EXPECT_EQ(validate_soup(soup, "m.obj"), 0u);
}

TEST(MeshColors, ObjWithoutTextureKeepsIndicesAndOnlyVertexColours) {
  TempDir dir;
  const TriangleSoup soup = load_mesh(dir.write("v.obj",
                                                "v 0 0 0 1 0 0\nv 1 0 0\nv 0 1 0 0 0 0.5\nvt 0 0\n"
                                                "f 1/1 2/1 3/1\n"));
  EXPECT_EQ(vec(soup.colors.vertex_rgba), (std::vector<uint32_t>{rgba(255, 0, 0), kWhite, rgba(0, 0, 128)}));
  EXPECT_TRUE(soup.colors.vertex_uv.empty());
  EXPECT_TRUE(soup.colors.looks.empty());
  // A missing library: a warning, and white.
  std::vector<std::string> warnings;
  const TriangleSoup plain = load_mesh(
      dir.write("n.obj", "mtllib none.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl a\nf 1 2 3\n"), &warnings);
  EXPECT_TRUE(plain.colors.empty());
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find("line 1: material library 'none.mtl' not found"), std::string::npos)
      << warnings[0];
}

TEST(MeshColors, ObjErrors) {
  TempDir dir;
  struct Case {
    const char* obj;
    const char* mtl;
    std::string file, message;
  };
  const Case cases[] = {
      {"mtllib l.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl a\nf 1 2 3\n", "newmtl a\nmap_Kd gone.png\n", "l.mtl",
       "line 2: texture"},
      {"v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1/1 2/2 3/1\n", "", "e.obj",
       "line 5: face corner '2/2' refers to texture coordinate 2 but 1 texture coordinates are defined "
       "before it"},
      {"v 0 0 0 1.5 0 0\n", "", "e.obj", "line 1: vertex colour '1.5' is not a number in [0, 1]"},
      {"vt 0 nan\n", "", "e.obj", "line 1: texture coordinate 'nan' is not a finite number"},
      {"mtllib l.mtl\n", "newmtl a\nKd 0.5 2 0\n", "l.mtl",
       "line 2: Kd component '2' is not a number in [0, 1]"},
      {"mtllib l.mtl\n", "newmtl a\nmap_Kd -s 2 2 1 t.png\n", "l.mtl",
       "line 2: map_Kd option '-s' is not supported"},
      {"mtllib l.mtl\n", "Kd 1 1 1\n", "l.mtl", "line 1: 'Kd' before any newmtl"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.obj);
    dir.write("l.mtl", c.mtl);
    const fs::path p = dir.write("e.obj", c.obj);
    const std::string m = error_of([&] { load_mesh(p); });
    expect_one_line(m, (dir.path() / c.file).string());
    EXPECT_NE(m.find(c.message), std::string::npos) << m;
  }
}

// ---- glTF through Assimp ----

// A glTF of one triangle with COLOR_0, TEXCOORD_0 and a material with a base colour factor and texture
// `image_uri`.
// `glb_png` empty: glTF JSON whose image is `image_uri`, the buffer a data URI; else a GLB whose binary
// chunk holds the geometry and then `glb_png`, the image a bufferView of it.
std::string gltf_triangle(const std::string& image_uri, const std::string& glb_png = "") {
  std::string bin;
  auto f32 = [&](float v) { bin.append(reinterpret_cast<const char*>(&v), 4); };
  for (float v : {0.f, 0.f, 0.f, 1.f, 0.f, 0.f, 0.f, 1.f, 0.f}) f32(v);                 // POSITION, 36 bytes
  for (float v : {1.f, 0.f, 0.f, 1.f, 0.f, 1.f, 0.f, .5f, 0.f, 0.f, 1.f, 0.f}) f32(v);  // COLOR_0, 48
  for (float v : {.25f, .25f, 1.f, 0.f, 0.f, 1.f}) f32(v);                              // TEXCOORD_0, 24
  const bool glb = !glb_png.empty();
  const std::string image =
      glb ? R"({"bufferView":3,"mimeType":"image/png"})" : R"({"uri":")" + image_uri + R"("})";
  const std::string image_view =
      glb ? R"(,{"buffer":0,"byteOffset":108,"byteLength":)" + std::to_string(glb_png.size()) + "}" : "";
  if (glb) bin += glb_png;
  while (bin.size() % 4) bin += '\0';
  const std::string buffer =
      glb ? R"({"byteLength":)" + std::to_string(bin.size()) + "}"
          : R"({"byteLength":108,"uri":"data:application/octet-stream;base64,)" + base64(bin) + R"("})";
  std::string json = R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],"nodes":[{"mesh":0}],
"meshes":[{"primitives":[{"attributes":{"POSITION":0,"COLOR_0":1,"TEXCOORD_0":2},"material":0}]}],
"materials":[{"pbrMetallicRoughness":{"baseColorFactor":[1,0.5,0.25,1],"baseColorTexture":{"index":0}}}],
"textures":[{"source":0}],"images":[)" +
                     image + R"(],"buffers":[)" + buffer + R"(],
"bufferViews":[{"buffer":0,"byteOffset":0,"byteLength":36},{"buffer":0,"byteOffset":36,"byteLength":48},
{"buffer":0,"byteOffset":84,"byteLength":24})" +
                     image_view + R"(],
"accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3","min":[0,0,0],"max":[1,1,0]},
{"bufferView":1,"componentType":5126,"count":3,"type":"VEC4"},
{"bufferView":2,"componentType":5126,"count":3,"type":"VEC2"}]})";
  if (!glb) return json;
  while (json.size() % 4) json += ' ';
  auto u32 = [](uint32_t v) { return std::string(reinterpret_cast<const char*>(&v), 4); };
  return "glTF" + u32(2) + u32(uint32_t(12 + 8 + json.size() + 8 + bin.size())) + u32(uint32_t(json.size())) +
         "JSON" + json + u32(uint32_t(bin.size())) + std::string("BIN\0", 4) + bin;
}

void expect_gltf_colours(const TriangleSoup& soup) {
  const SoupColors& c = soup.colors;
  ASSERT_EQ(soup.vertex_count(), 3u);
  EXPECT_EQ(vec(c.vertex_rgba),
            (std::vector<uint32_t>{rgba(255, 0, 0, 255), rgba(0, 255, 0, 128), rgba(0, 0, 255, 0)}));
  // glTF's v points down from the image's top; Assimp flips it to v up, the soup's convention.
  EXPECT_EQ(vec(c.vertex_uv), (std::vector<glm::vec2>{{0.25f, 0.75f}, {1.f, 1.f}, {0.f, 0.f}}));
  ASSERT_EQ(c.looks.size(), 1u);
  EXPECT_EQ(c.looks[0].factor_rgba, rgba(255, 128, 64, 255));
  EXPECT_EQ(c.looks[0].texture, 0);
  EXPECT_TRUE(c.triangle_look.empty());
  ASSERT_EQ(c.textures.size(), 1u);
  EXPECT_EQ(c.textures[0].texels, std::vector<uint32_t>(kTexels, kTexels + 4));
}

TEST(MeshColors, GltfExternalTexture) {
  TempDir dir;
  write_png(dir, "tex.png");
  expect_gltf_colours(load_mesh(dir.write("t.gltf", gltf_triangle("tex.png"))));
  // A path from another machine: the file name beside the mesh.
  expect_gltf_colours(load_mesh(dir.write("w.gltf", gltf_triangle("textures/old/tex.png"))));
  fs::remove(dir.path() / "tex.png");
  const fs::path p = dir.path() / "t.gltf";
  const std::string m = error_of([&] { load_mesh(p); });
  expect_one_line(m, p.string());
  EXPECT_NE(m.find("tex.png"), std::string::npos) << m;
}

TEST(MeshColors, GltfEmbeddedTexture) {
  TempDir dir;
  const std::string png = file_text(write_png(dir, "tex.png"));
  const TriangleSoup soup =
      load_mesh(dir.write("e.gltf", gltf_triangle("data:image/png;base64," + base64(png))));
  expect_gltf_colours(soup);
  ASSERT_EQ(soup.colors.textures.size(), 1u);
  EXPECT_NE(soup.colors.textures[0].source.find("(embedded texture '*0')"), std::string::npos);
  // GLB: the image in a bufferView of the binary chunk.
  const TriangleSoup glb = load_mesh(dir.write("e.glb", gltf_triangle("", png)));
  expect_gltf_colours(glb);
  ASSERT_EQ(glb.colors.textures.size(), 1u);
  EXPECT_NE(glb.colors.textures[0].source.find("(embedded texture '*0')"), std::string::npos);
}

// ---- soup operations ----

// One triangle with a colour per vertex, UVs, two looks (the second textured) and one texture.
TriangleSoup coloured_triangle() {
  TriangleSoup s;
  s.positions = {glm::vec4(0, 0, 0, 1), glm::vec4(1, 0, 0, 1), glm::vec4(0, 1, 0, 1)};
  s.triangles = {{0, 1, 2, 3}};
  s.colors.vertex_rgba = {rgba(255, 0, 0), rgba(0, 255, 0), rgba(0, 0, 255, 1)};
  s.colors.vertex_uv = {{0, 0}, {1, 0}, {0, 1}};
  s.colors.triangle_look = {1};
  s.colors.looks = {SurfaceLook{rgba(9, 9, 9), -1}, SurfaceLook{kWhite, 0}};
  s.colors.textures = {SoupTexture{1, 1, {rgba(1, 2, 3)}, "t.png"}};
  return s;
}

TriangleSoup plain_triangle() {
  TriangleSoup s;
  s.positions = {glm::vec4(0, 0, 1, 1), glm::vec4(1, 0, 1, 1), glm::vec4(0, 1, 1, 1)};
  s.triangles = {{0, 1, 2, 5}};
  return s;
}

TEST(MeshColors, AppendFillsMissingArraysAndOffsetsIndices) {
  TriangleSoup a = coloured_triangle();
  a.append(plain_triangle());
  EXPECT_EQ(vec(a.colors.vertex_rgba), (std::vector<uint32_t>{rgba(255, 0, 0), rgba(0, 255, 0),
                                                              rgba(0, 0, 255, 1), kWhite, kWhite, kWhite}));
  EXPECT_EQ(vec(a.colors.vertex_uv),
            (std::vector<glm::vec2>{{0, 0}, {1, 0}, {0, 1}, {0, 0}, {0, 0}, {0, 0}}));
  EXPECT_EQ(vec(a.colors.triangle_look), (std::vector<uint32_t>{1, 2}));
  ASSERT_EQ(a.colors.looks.size(), 3u);
  EXPECT_EQ(a.colors.looks[2].factor_rgba, kWhite);
  EXPECT_EQ(a.colors.looks[2].texture, -1);
  EXPECT_EQ(validate_soup(a, "a"), 0u);

  TriangleSoup b = plain_triangle();
  b.append(coloured_triangle(), glm::mat4(2.0f));
  EXPECT_EQ(vec(b.colors.vertex_rgba), (std::vector<uint32_t>{kWhite, kWhite, kWhite, rgba(255, 0, 0),
                                                              rgba(0, 255, 0), rgba(0, 0, 255, 1)}));
  EXPECT_EQ(vec(b.colors.triangle_look), (std::vector<uint32_t>{0, 2}));
  ASSERT_EQ(b.colors.looks.size(), 3u);
  EXPECT_EQ(b.colors.looks[0].factor_rgba, kWhite);
  EXPECT_EQ(b.colors.looks[2].texture, 0);
  ASSERT_EQ(b.colors.textures.size(), 1u);
  EXPECT_EQ(validate_soup(b, "b"), 0u);
  // The same texture appended again is shared.
  b.append(coloured_triangle());
  EXPECT_EQ(b.colors.textures.size(), 1u);
  EXPECT_EQ(vec(b.colors.triangle_look), (std::vector<uint32_t>{0, 2, 4}));
  EXPECT_EQ(b.colors.looks[4].texture, 0);

  TriangleSoup c = plain_triangle();
  c.append(plain_triangle());
  EXPECT_TRUE(c.colors.empty());
  EXPECT_EQ(c.colors.vertex_rgba.capacity() + c.colors.triangle_look.capacity(), 0u);
}

TEST(MeshColors, ValidateSoupChecksColours) {
  auto message = [](auto change) {
    TriangleSoup s = coloured_triangle();
    change(s.colors);
    return error_of([&] { validate_soup(s, "src"); });
  };
  EXPECT_EQ(message([](SoupColors& c) { c.vertex_rgba.pop_back(); }), "src: 2 vertex colours for 3 vertices");
  EXPECT_EQ(message([](SoupColors& c) { c.vertex_uv[1].y = NAN; }),
            "src: vertex 1 has texture coordinates (1, nan) that are not finite");
  EXPECT_EQ(message([](SoupColors& c) { c.triangle_look[0] = 2; }),
            "src: triangle 0 uses look 2 but there are 2 looks");
  EXPECT_EQ(message([](SoupColors& c) { c.looks[1].texture = 1; }),
            "src: look 1 uses texture 1 but there are 1 textures");
  EXPECT_EQ(message([](SoupColors& c) { c.textures[0].texels.clear(); }),
            "src: texture 0 (t.png) has 0 texels for 1x1");
  EXPECT_EQ(message([](SoupColors&) {}), "");
}

TEST(MeshColors, SplitterInterpolatesColoursAndKeepsLooks) {
  TriangleSoup soup;
  soup.positions = {glm::vec4(1, 1, 1, 1), glm::vec4(2, 1, 1, 1),    glm::vec4(1, 2, 1, 1),
                    glm::vec4(0, 0, 1, 1), glm::vec4(3000, 0, 1, 1), glm::vec4(0, 3000, 1, 1)};
  soup.triangles = {{0, 1, 2, 0}, {3, 4, 5, 7}};
  soup.colors.vertex_rgba = {kWhite, kWhite, kWhite, rgba(255, 0, 0), rgba(0, 255, 0), rgba(0, 0, 255, 1)};
  soup.colors.vertex_uv = {{0, 0}, {0, 0}, {0, 0}, {0, 0}, {1, 0}, {0, 1}};
  soup.colors.triangle_look = {1, 0};
  soup.colors.looks = {SurfaceLook{}, SurfaceLook{rgba(1, 1, 1), -1}};
  GridSpec grid;
  grid.dims = glm::uvec3(3001, 3001, 2);
  uint64_t split = 0;
  const std::optional<TriangleSoup> out = split_oversized_triangles(soup, grid, &split);
  ASSERT_TRUE(out.has_value());
  EXPECT_EQ(split, 1u);
  ASSERT_EQ(out->triangle_count(), 5u);
  ASSERT_EQ(out->vertex_count(), 6u + 12u);
  EXPECT_EQ(vec(out->colors.triangle_look), (std::vector<uint32_t>{1, 0, 0, 0, 0}));
  EXPECT_EQ(out->colors.looks.size(), 2u);
  const uint32_t r = rgba(255, 0, 0), g = rgba(0, 255, 0), b = rgba(0, 0, 255, 1);
  const uint32_t rg = rgba(128, 128, 0), gb = rgba(0, 128, 128, 128), br = rgba(128, 0, 128, 128);
  const glm::vec2 u0(0, 0), u1(1, 0), u2(0, 1), u01(0.5f, 0), u12(0.5f, 0.5f), u20(0, 0.5f);
  // Pieces {a, ab, ca}, {ab, b, bc}, {ca, bc, c}, {ab, bc, ca}, each with its own three vertices.
  const std::vector<uint32_t> want_rgba = {kWhite, kWhite, kWhite, r,  g,  b, r,  rg, br,
                                           rg,     g,      gb,     br, gb, b, rg, gb, br};
  const std::vector<glm::vec2> want_uv = {u0,  u0, u0,  u0,  u1,  u2, u0,  u01, u20,
                                          u01, u1, u12, u20, u12, u2, u01, u12, u20};
  EXPECT_EQ(vec(out->colors.vertex_rgba), want_rgba);
  EXPECT_EQ(vec(out->colors.vertex_uv), want_uv);
  for (size_t t = 1; t < 5; ++t) EXPECT_EQ(out->triangles[t].w, 7u);
  EXPECT_EQ(validate_soup(*out, "split"), 0u);
}

TEST(MeshColors, SubdivideAndDuplicateRemovalKeepColours) {
  TriangleSoup s = coloured_triangle();
  const TriangleSoup d = subdivide_midpoint(s, 1);
  ASSERT_EQ(d.vertex_count(), 6u);
  EXPECT_EQ(vec(d.colors.vertex_rgba),
            (std::vector<uint32_t>{rgba(255, 0, 0), rgba(0, 255, 0), rgba(0, 0, 255, 1), rgba(128, 128, 0),
                                   rgba(0, 128, 128, 128), rgba(128, 0, 128, 128)}));
  EXPECT_EQ(vec(d.colors.vertex_uv),
            (std::vector<glm::vec2>{{0, 0}, {1, 0}, {0, 1}, {0.5f, 0}, {0.5f, 0.5f}, {0, 0.5f}}));
  EXPECT_EQ(vec(d.colors.triangle_look), (std::vector<uint32_t>{1, 1, 1, 1}));
  EXPECT_EQ(validate_soup(d, "d"), 0u);

  s.append(coloured_triangle());  // a duplicate of the first triangle
  s.append(plain_triangle());
  ASSERT_EQ(vec(s.colors.triangle_look), (std::vector<uint32_t>{1, 3, 4}));
  EXPECT_EQ(drop_duplicate_triangles(s), 1u);
  EXPECT_EQ(vec(s.colors.triangle_look), (std::vector<uint32_t>{1, 4}));
  EXPECT_EQ(validate_soup(s, "s"), 0u);
}

TEST(MeshColors, ScenesKeepColoursOfEachMesh) {
  TempDir dir;
  dir.write("c.off", "COFF\n3 1 0\n0 0 0 255 0 0\n1 0 0 0 255 0\n0 1 0 0 0 255\n3 0 1 2\n");
  dir.write("f.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2 0 0 255\n");
  const std::string meshes =
      R"("meshes": [{"generator": "box"}, {"file": "c.off", "transform": {"scale": [-1, 2, 1]}},
                    {"file": "f.off")";
  for (const char* animation :
       {"}]", R"(, "animation": {"keys": [{"time": 0}, {"time": 1, "translate": [1, 0, 0]}]}}])"}) {
    SCOPED_TRACE(animation);
    const Scene scene = load_scene(dir.write("s.json", std::string("{") + meshes + animation + "}"));
    const TriangleSoup soup = scene_triangles(scene);
    const size_t box = scene.meshes[0].soup.vertex_count(),
                 box_triangles = scene.meshes[0].soup.triangle_count();
    ASSERT_EQ(soup.vertex_count(), box + 6);
    std::vector<uint32_t> want(box, kWhite);
    for (uint32_t c : {rgba(255, 0, 0), rgba(0, 255, 0), rgba(0, 0, 255), kWhite, kWhite, kWhite})
      want.push_back(c);
    EXPECT_EQ(vec(soup.colors.vertex_rgba), want);
    std::vector<uint32_t> looks(box_triangles + 1, 0u);
    looks.push_back(1u);  // white look 0 for the meshes before the first with looks
    EXPECT_EQ(vec(soup.colors.triangle_look), looks);
    ASSERT_EQ(soup.colors.looks.size(), 2u);
    EXPECT_EQ(soup.colors.looks[0].factor_rgba, kWhite);
    EXPECT_EQ(soup.colors.looks[1].factor_rgba, rgba(0, 0, 255));
    EXPECT_EQ(validate_soup(soup, "s.json"), 0u);
  }
}

}  // namespace
}  // namespace voxr
