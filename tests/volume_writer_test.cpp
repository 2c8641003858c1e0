// Volume writers: every format is parsed back by a small reader here and compared with the grid.
#include <gtest/gtest.h>

#include <signal.h>
#include <sys/resource.h>
#include <unistd.h>

#include <array>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "io/binvox_writer.h"
#include "io/nrrd_writer.h"
#include "io/volume_writer.h"
#include "io/vox_writer.h"
#include "io/vti_writer.h"
#include "util/error.h"
#include "cli_support.h"
#include "test_support.h"
#include "voxr_layout.h"

namespace voxr {
namespace {

using test::listing;
using test::slurp;

namespace fs = std::filesystem;

// ---- grid construction -----------------------------------------------------------------------------------

uint32_t count_of(uint64_t linear) {
  return uint32_t(linear % 7 + 1);
}
uint32_t material_of(uint64_t linear) {
  return uint32_t(linear * 37 + 250);
}  // crosses the % 255 wrap
glm::vec3 normal_of(uint64_t linear) {
  return glm::normalize(glm::vec3(float(linear % 3) - 1.0f, 0.5f, float(linear % 5) * 0.25f + 0.1f));
}

VoxelGrid make_grid(const GridSpec& spec, const std::vector<glm::uvec3>& voxels, bool attributes = true) {
  VoxelGrid g;
  g.spec = spec;
  g.occ.assign(size_t((spec.voxel_count() + 31) / 32), 0u);
  for (const glm::uvec3& v : voxels) {
    const uint64_t l = spec.linear_index(v.x, v.y, v.z);
    g.occ[l >> 5] |= 1u << (l & 31);
  }
  if (attributes) {
    g.channels = ChannelSet::parse("occ,count,normal,material");
    g.for_each_set([&](uint64_t linear, uint64_t) {
      g.count.push_back(count_of(linear));
      g.normal.push_back(normal_of(linear));
      g.normal_sum.push_back(glm::ivec3(glm::round(normal_of(linear) * float(VOXR_NORMAL_ONE))));
      g.material.push_back(material_of(linear));
    });
  }
  g.for_each_set([&](uint64_t, uint64_t) { ++g.voxels_set; });
  return g;
}

GridSpec spec_of(glm::uvec3 dims, float h = 0.5f, glm::vec3 origin = {1.0f, -2.0f, 3.25f}) {
  GridSpec s;
  s.dims = dims;
  s.voxel_size = h;
  s.origin = origin;
  return s;
}

// 5x4x3 with an asymmetric handful: any axis swap or flip changes the set.
VoxelGrid small_grid() {
  return make_grid(spec_of({5, 4, 3}),
                   {{0, 0, 0}, {1, 0, 0}, {4, 0, 0}, {0, 3, 0}, {2, 1, 1}, {0, 0, 2}, {4, 3, 2}, {3, 2, 2}});
}

template <typename T>
T load(const std::string& bytes, size_t offset) {
  T v;
  EXPECT_LE(offset + sizeof(T), bytes.size());
  std::memcpy(&v, bytes.data() + offset, sizeof(T));
  return v;
}

// Dense reference arrays in linear order.
std::vector<uint8_t> dense_occ(const VoxelGrid& g) {
  std::vector<uint8_t> v(g.spec.voxel_count(), 0);
  g.for_each_set([&](uint64_t l, uint64_t) { v[l] = 1; });
  return v;
}
std::vector<uint32_t> dense_u32(const VoxelGrid& g, uint32_t (*fn)(uint64_t)) {
  std::vector<uint32_t> v(g.spec.voxel_count(), 0);
  g.for_each_set([&](uint64_t l, uint64_t) { v[l] = fn(l); });
  return v;
}
std::vector<float> dense_normal(const VoxelGrid& g) {
  std::vector<float> v(g.spec.voxel_count() * 3, 0.0f);
  g.for_each_set([&](uint64_t l, uint64_t r) {
    for (int c = 0; c < 3; ++c) v[l * 3 + c] = g.normal[r][c];
  });
  return v;
}

template <typename T>
std::string bytes_of(const std::vector<T>& v) {
  return std::string(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(T));
}

// ---- NRRD ------------------------------------------------------------------------------------------------

struct Nrrd {
  std::string magic;
  std::map<std::string, std::string> fields;
  std::string data;
};

Nrrd read_nrrd(const fs::path& p) {
  const std::string s = slurp(p);
  const size_t end = s.find("\n\n");
  EXPECT_NE(end, std::string::npos);
  Nrrd n;
  n.data = s.substr(end + 2);
  std::istringstream lines(s.substr(0, end));
  std::getline(lines, n.magic);
  for (std::string line; std::getline(lines, line);) {
    if (line.empty() || line[0] == '#') continue;
    const size_t colon = line.find(": ");
    EXPECT_NE(colon, std::string::npos) << line;
    n.fields[line.substr(0, colon)] = line.substr(colon + 2);
  }
  return n;
}

std::vector<float> parse_floats(std::string text) {
  for (char& c : text)
    if (c == '(' || c == ')' || c == ',') c = ' ';
  std::istringstream in(text);
  std::vector<float> v;
  for (float f; in >> f;) v.push_back(f);
  return v;
}

TEST(VolumeWriter, NrrdOccupancyAndChannelSiblings) {
  const test::TempDir folder;
  const fs::path& dir = folder.path();
  const VoxelGrid g = small_grid();
  const fs::path out = dir / "scene.nrrd";
  const auto written = write_volume(g, out);
  ASSERT_EQ(written, (std::vector<fs::path>{out, dir / "scene.count.nrrd", dir / "scene.normal.nrrd",
                                            dir / "scene.material.nrrd"}));
  EXPECT_EQ(listing(dir), (std::set<std::string>{"scene.nrrd", "scene.count.nrrd", "scene.normal.nrrd",
                                                 "scene.material.nrrd"}));  // no temp files left

  const glm::vec3 c0 = g.spec.voxel_center_world(0, 0, 0);
  EXPECT_EQ(c0, glm::vec3(1.25f, -1.75f, 3.5f));
  auto check_common = [&](const Nrrd& n, bool vector) {
    EXPECT_EQ(n.magic, "NRRD0004");
    EXPECT_EQ(n.fields.at("dimension"), vector ? "4" : "3");
    EXPECT_EQ(n.fields.at("sizes"), vector ? "3 5 4 3" : "5 4 3");
    EXPECT_EQ(n.fields.at("endian"), "little");
    EXPECT_EQ(n.fields.at("encoding"), "raw");
    EXPECT_EQ(n.fields.at("space"), "right-anterior-superior");
    EXPECT_EQ(n.fields.at("kinds"), vector ? "3-vector domain domain domain" : "domain domain domain");
    EXPECT_EQ(n.fields.at("centers"), vector ? "none cell cell cell" : "cell cell cell");
    EXPECT_EQ(parse_floats(n.fields.at("space origin")), (std::vector<float>{c0.x, c0.y, c0.z}));
    std::string dirs = n.fields.at("space directions");
    if (vector) {
      ASSERT_EQ(dirs.rfind("none ", 0), 0u) << dirs;
      dirs = dirs.substr(5);
    }
    EXPECT_EQ(parse_floats(dirs), (std::vector<float>{0.5f, 0, 0, 0, 0.5f, 0, 0, 0, 0.5f}));
  };

  const Nrrd occ = read_nrrd(out);
  check_common(occ, false);
  EXPECT_EQ(occ.fields.at("type"), "uint8");
  EXPECT_EQ(occ.data, bytes_of(dense_occ(g)));

  const Nrrd count = read_nrrd(dir / "scene.count.nrrd");
  check_common(count, false);
  EXPECT_EQ(count.fields.at("type"), "uint32");
  EXPECT_EQ(count.data, bytes_of(dense_u32(g, count_of)));

  const Nrrd normal = read_nrrd(dir / "scene.normal.nrrd");
  check_common(normal, true);
  EXPECT_EQ(normal.fields.at("type"), "float");
  EXPECT_EQ(normal.data, bytes_of(dense_normal(g)));

  const Nrrd material = read_nrrd(dir / "scene.material.nrrd");
  check_common(material, false);
  EXPECT_EQ(material.fields.at("type"), "uint32");
  EXPECT_EQ(material.data, bytes_of(dense_u32(g, material_of)));
}

TEST(VolumeWriter, NrrdOccupancyOnlyAndRotatedAxes) {
  const test::TempDir folder;
  const fs::path& dir = folder.path();
  GridSpec spec = spec_of({5, 4, 3}, 2.0f, {0, 0, 0});
  spec.axes = glm::mat3(glm::vec3(0, 1, 0), glm::vec3(-1, 0, 0), glm::vec3(0, 0, 1));  // 90 deg about z
  const VoxelGrid g = make_grid(spec, {{1, 2, 0}, {4, 3, 2}}, /*attributes=*/false);
  const auto written = write_volume(g, dir / "occ.NRRD");
  ASSERT_EQ(written, (std::vector<fs::path>{dir / "occ.NRRD"}));
  const Nrrd n = read_nrrd(dir / "occ.NRRD");
  EXPECT_EQ(parse_floats(n.fields.at("space directions")), (std::vector<float>{0, 2, 0, -2, 0, 0, 0, 0, 2}));
  EXPECT_EQ(parse_floats(n.fields.at("space origin")), (std::vector<float>{-1, 1, 1}));
  EXPECT_EQ(n.data, bytes_of(dense_occ(g)));
}

TEST(VolumeWriter, NrrdStreamsAcrossChunks) {
  // More than one 2^20-voxel chunk, voxels on both sides of the boundary, and channels via normal_sum only.
  const test::TempDir folder;
  const fs::path& dir = folder.path();
  const GridSpec spec = spec_of({128, 128, 80});
  std::vector<glm::uvec3> voxels;
  for (uint64_t l : {uint64_t(0), uint64_t(31), uint64_t(32), uint64_t(1048575), uint64_t(1048576),
                     uint64_t(1048577), spec.voxel_count() - 1})
    voxels.push_back({uint32_t(l % 128), uint32_t(l / 128 % 128), uint32_t(l / (128 * 128))});
  VoxelGrid g = make_grid(spec, voxels);
  g.normal.clear();  // the writer normalizes normal_sum instead
  write_volume(g, dir / "big.nrrd");
  EXPECT_EQ(read_nrrd(dir / "big.nrrd").data, bytes_of(dense_occ(g)));
  EXPECT_EQ(read_nrrd(dir / "big.count.nrrd").data, bytes_of(dense_u32(g, count_of)));
  const std::string normals = read_nrrd(dir / "big.normal.nrrd").data;
  g.for_each_set([&](uint64_t l, uint64_t) {
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(load<float>(normals, (l * 3 + c) * 4), normal_of(l)[c], 2e-3f);
  });
}

// ---- binvox ----------------------------------------------------------------------------------------------

struct Binvox {
  std::string header;
  uint32_t dim = 0;
  std::vector<float> translate;
  float scale = 0;
  std::vector<uint8_t> voxels;  // binvox order
};

Binvox read_binvox(const fs::path& p) {
  const std::string s = slurp(p);
  const size_t data = s.find("data\n");
  EXPECT_NE(data, std::string::npos);
  Binvox b;
  b.header = s.substr(0, data + 5);
  std::istringstream in(b.header);
  std::string word;
  in >> word >> word;  // "#binvox 1"
  uint32_t dy, dz;
  in >> word >> b.dim >> dy >> dz;
  EXPECT_EQ(word, "dim");
  b.translate.resize(3);
  in >> word >> b.translate[0] >> b.translate[1] >> b.translate[2];
  EXPECT_EQ(word, "translate");
  in >> word >> b.scale;
  EXPECT_EQ(word, "scale");
  for (size_t i = data + 5; i + 1 < s.size(); i += 2) {
    const uint8_t value = uint8_t(s[i]), run = uint8_t(s[i + 1]);
    EXPECT_TRUE(value == 0 || value == 1);
    EXPECT_GE(run, 1);
    b.voxels.insert(b.voxels.end(), run, value);
  }
  EXPECT_EQ((s.size() - data - 5) % 2, 0u);
  return b;
}

void expect_binvox_matches(const VoxelGrid& g, const Binvox& b) {
  const uint32_t d = g.spec.dims.x;
  ASSERT_EQ(b.voxels.size(), size_t(d) * d * d);
  for (uint32_t x = 0; x < d; ++x)
    for (uint32_t y = 0; y < d; ++y)
      for (uint32_t z = 0; z < d; ++z)
        ASSERT_EQ(b.voxels[size_t(x) * d * d + size_t(z) * d + y], g.occupied(x, y, z) ? 1 : 0)
            << x << " " << y << " " << z;
}

TEST(VolumeWriter, BinvoxOrderAndHeader) {
  const test::TempDir folder;
  const fs::path& dir = folder.path();
  // Asymmetric: voxels differ under any permutation of the axes.
  const VoxelGrid g = make_grid(spec_of({4, 4, 4}), {{1, 0, 0}, {0, 2, 0}, {0, 0, 3}, {3, 1, 2}, {2, 3, 3}});
  ASSERT_EQ(write_volume(g, dir / "g.binvox"), (std::vector<fs::path>{dir / "g.binvox"}));
  const Binvox b = read_binvox(dir / "g.binvox");
  EXPECT_EQ(b.header, "#binvox 1\ndim 4 4 4\ntranslate 1 -2 3.25\nscale 2\ndata\n");
  EXPECT_EQ(b.dim, 4u);
  EXPECT_EQ(b.translate, (std::vector<float>{1.0f, -2.0f, 3.25f}));
  EXPECT_EQ(b.scale, 2.0f);
  expect_binvox_matches(g, b);
  // binvox's voxel centre convention maps back to voxr's centres.
  const glm::vec3 c = g.spec.voxel_center_world(3, 1, 2);
  for (int a = 0; a < 3; ++a)
    EXPECT_FLOAT_EQ((float(glm::uvec3(3, 1, 2)[a]) + 0.5f) / float(b.dim) * b.scale + b.translate[a], c[a]);
  EXPECT_EQ(listing(dir), std::set<std::string>{"g.binvox"});
}

TEST(VolumeWriter, BinvoxLongRunsAndSeveralXBlocks) {
  const test::TempDir folder;
  const fs::path& dir = folder.path();
  const uint32_t d = 70;  // two 64-wide x blocks, runs longer than 255
  std::vector<glm::uvec3> voxels;
  for (uint32_t z = 0; z < d; ++z)
    for (uint32_t y = 0; y < d; ++y)
      for (uint32_t x = 0; x < d; ++x)
        if ((x * 7 + y * 3 + z * 11) % 13 == 0 || (z > 60 && y < 10)) voxels.push_back({x, y, z});
  const VoxelGrid g = make_grid(spec_of({d, d, d}), voxels, false);
  write_volume(g, dir / "big.binvox");
  expect_binvox_matches(g, read_binvox(dir / "big.binvox"));
}

// ---- vox -------------------------------------------------------------------------------------------------

TEST(VolumeWriter, VoxChunksAndAxisMapping) {
  const test::TempDir folder;
  const fs::path& dir = folder.path();
  const VoxelGrid g = small_grid();
  ASSERT_EQ(write_volume(g, dir / "g.vox"), (std::vector<fs::path>{dir / "g.vox"}));
  const std::string s = slurp(dir / "g.vox");
  ASSERT_EQ(s.substr(0, 4), "VOX ");
  EXPECT_EQ(load<int32_t>(s, 4), 150);
  ASSERT_EQ(s.substr(8, 4), "MAIN");
  EXPECT_EQ(load<int32_t>(s, 12), 0);
  EXPECT_EQ(size_t(load<int32_t>(s, 16)), s.size() - 20);

  std::map<std::string, std::string> chunks;
  for (size_t at = 20; at < s.size();) {
    const std::string id = s.substr(at, 4);
    const int32_t content = load<int32_t>(s, at + 4);
    EXPECT_EQ(load<int32_t>(s, at + 8), 0);
    chunks[id] = s.substr(at + 12, size_t(content));
    at += 12 + size_t(content);
  }
  ASSERT_EQ(chunks.size(), 3u);
  // voxr (x, y, z) -> vox (x, Dz-1-z, y); SIZE = (Dx, Dz, Dy).
  const std::string& size = chunks.at("SIZE");
  ASSERT_EQ(size.size(), 12u);
  EXPECT_EQ(load<int32_t>(size, 0), 5);
  EXPECT_EQ(load<int32_t>(size, 4), 3);
  EXPECT_EQ(load<int32_t>(size, 8), 4);

  const std::string& xyzi = chunks.at("XYZI");
  const int32_t n = load<int32_t>(xyzi, 0);
  ASSERT_EQ(uint64_t(n), g.voxels_set);
  ASSERT_EQ(xyzi.size(), 4 + 4 * size_t(n));
  std::set<std::array<int, 4>> got, want;
  for (int32_t v = 0; v < n; ++v) {
    const auto* p = reinterpret_cast<const uint8_t*>(xyzi.data() + 4 + 4 * v);
    got.insert({p[0], p[1], p[2], p[3]});
  }
  g.for_each_set([&](uint64_t l, uint64_t) {
    const int x = int(l % 5), y = int(l / 5 % 4), z = int(l / 20);
    want.insert({x, 2 - z, y, int(1 + material_of(l) % 255)});
  });
  EXPECT_EQ(got, want);
  // Upright: voxr's +y (up) is vox +z; voxr's +x stays +x; voxr's +z (towards the viewer) is vox -y.
  EXPECT_EQ(vox_coords({0, 3, 0}, {5, 4, 3}), glm::uvec3(0, 2, 3));
  EXPECT_EQ(vox_coords({0, 0, 2}, {5, 4, 3}), glm::uvec3(0, 0, 0));

  const std::string& rgba = chunks.at("RGBA");
  ASSERT_EQ(rgba.size(), 1024u);
  for (int i = 0; i < 256; ++i) EXPECT_EQ(uint8_t(rgba[4 * i + 3]), 255);
}

TEST(VolumeWriter, VoxWithoutMaterialUsesColourOne) {
  const test::TempDir folder;
  const fs::path& dir = folder.path();
  const VoxelGrid g = make_grid(spec_of({256, 2, 1}), {{255, 1, 0}, {0, 0, 0}}, false);
  write_volume(g, dir / "g.vox");
  const std::string s = slurp(dir / "g.vox");
  // MAIN header (20) + SIZE (12 + 12) -> XYZI chunk header at 44, count at 56.
  ASSERT_EQ(s.substr(44, 4), "XYZI");
  ASSERT_EQ(load<int32_t>(s, 56), 2);
  EXPECT_EQ(s.substr(60, 8), std::string("\x00\x00\x00\x01\xff\x00\x01\x01", 8));
}

// ---- vti -------------------------------------------------------------------------------------------------

std::string attribute(const std::string& xml, const std::string& element_start, const std::string& name) {
  const size_t e = xml.find(element_start);
  EXPECT_NE(e, std::string::npos) << element_start;
  if (e == std::string::npos) return {};
  const size_t close = xml.find('>', e);
  const std::string tag = xml.substr(e, close - e);
  const size_t a = tag.find(" " + name + "=\"");
  if (a == std::string::npos) return "<missing>";
  const size_t begin = a + name.size() + 3;
  return tag.substr(begin, tag.find('"', begin) - begin);
}

TEST(VolumeWriter, VtiHeaderAndAppendedData) {
  const test::TempDir folder;
  const fs::path& dir = folder.path();
  GridSpec spec = spec_of({5, 4, 3});
  spec.axes = glm::mat3(glm::vec3(0, 1, 0), glm::vec3(-1, 0, 0), glm::vec3(0, 0, 1));
  VoxelGrid g = small_grid();
  g.spec = spec;
  ASSERT_EQ(write_volume(g, dir / "g.vti"), (std::vector<fs::path>{dir / "g.vti"}));
  const std::string s = slurp(dir / "g.vti");
  const size_t marker = s.find("<AppendedData encoding=\"raw\">");
  ASSERT_NE(marker, std::string::npos);
  const std::string xml = s.substr(0, marker);
  const size_t base = s.find('_', marker) + 1;

  EXPECT_EQ(attribute(xml, "<VTKFile", "type"), "ImageData");
  EXPECT_EQ(attribute(xml, "<VTKFile", "byte_order"), "LittleEndian");
  EXPECT_EQ(attribute(xml, "<VTKFile", "header_type"), "UInt64");
  EXPECT_EQ(attribute(xml, "<ImageData", "WholeExtent"), "0 4 0 3 0 2");
  EXPECT_EQ(attribute(xml, "<Piece", "Extent"), "0 4 0 3 0 2");
  const glm::vec3 c0 = spec.voxel_center_world(0, 0, 0);
  EXPECT_EQ(parse_floats(attribute(xml, "<ImageData", "Origin")), (std::vector<float>{c0.x, c0.y, c0.z}));
  EXPECT_EQ(parse_floats(attribute(xml, "<ImageData", "Spacing")), (std::vector<float>{0.5f, 0.5f, 0.5f}));
  // Row-major, columns = grid axes: x axis = world +y, y axis = world -x.
  EXPECT_EQ(parse_floats(attribute(xml, "<ImageData", "Direction")),
            (std::vector<float>{0, -1, 0, 1, 0, 0, 0, 0, 1}));

  struct Expected {
    std::string name, type, components, data;
  };
  const std::vector<Expected> arrays{
      {"occupancy", "UInt8", "<missing>", bytes_of(dense_occ(g))},
      {"count", "UInt32", "<missing>", bytes_of(dense_u32(g, count_of))},
      {"normal", "Float32", "3", bytes_of(dense_normal(g))},
      {"material", "UInt32", "<missing>", bytes_of(dense_u32(g, material_of))},
  };
  size_t end = base;
  for (const Expected& a : arrays) {
    const std::string element = "<DataArray type=\"" + a.type + "\" Name=\"" + a.name + "\"";
    ASSERT_NE(xml.find(element), std::string::npos) << a.name;
    EXPECT_EQ(attribute(xml, element, "format"), "appended");
    EXPECT_EQ(attribute(xml, element, "NumberOfComponents"), a.components);
    const size_t at = base + std::stoull(attribute(xml, element, "offset"));
    EXPECT_EQ(at, end) << a.name << ": arrays are packed back to back";
    const uint64_t bytes = load<uint64_t>(s, at);
    ASSERT_EQ(bytes, a.data.size()) << a.name;
    EXPECT_EQ(s.substr(at + 8, bytes), a.data) << a.name;
    end = at + 8 + bytes;
  }
  EXPECT_EQ(s.substr(end), "\n  </AppendedData>\n</VTKFile>\n");
}

TEST(VolumeWriter, InsideChannelRoundTrip) {
  // The dense interior bits next to occupancy and the sparse channels: NRRD sibling and VTI array, uint8 0/1.
  const test::TempDir folder;
  const fs::path& dir = folder.path();
  VoxelGrid g = small_grid();
  g.channels.add(Channel::kInside);
  g.inside.assign(g.occ.size(), 0u);
  std::vector<uint8_t> dense(g.spec.voxel_count(), 0);
  for (const glm::uvec3 v :
       {glm::uvec3(1, 1, 1), glm::uvec3(2, 1, 1), glm::uvec3(3, 2, 1), glm::uvec3(4, 3, 2)}) {
    const uint64_t l = g.spec.linear_index(v.x, v.y, v.z);
    g.inside[l >> 5] |= 1u << (l & 31);
    dense[l] = 1;
    ++g.inside_voxels;
  }
  const auto written = write_volume(g, dir / "s.nrrd");
  ASSERT_EQ(written.size(), 5u);
  EXPECT_EQ(written.back(), dir / "s.inside.nrrd");
  const Nrrd n = read_nrrd(dir / "s.inside.nrrd");
  EXPECT_EQ(n.fields.at("type"), "uint8");
  EXPECT_EQ(n.fields.at("sizes"), "5 4 3");
  EXPECT_EQ(n.data, bytes_of(dense));
  EXPECT_EQ(read_nrrd(dir / "s.nrrd").data, bytes_of(dense_occ(g)));

  write_volume(g, dir / "s.vti");
  const std::string s = slurp(dir / "s.vti");
  const size_t marker = s.find("<AppendedData encoding=\"raw\">");
  ASSERT_NE(marker, std::string::npos);
  const std::string xml = s.substr(0, marker);
  const std::string element = "<DataArray type=\"UInt8\" Name=\"inside\"";
  ASSERT_NE(xml.find(element), std::string::npos);
  const size_t at = s.find('_', marker) + 1 + std::stoull(attribute(xml, element, "offset"));
  ASSERT_EQ(load<uint64_t>(s, at), dense.size());
  EXPECT_EQ(s.substr(at + 8, dense.size()), bytes_of(dense));
  EXPECT_EQ(s.substr(at + 8 + dense.size()), "\n  </AppendedData>\n</VTKFile>\n");  // the last array
}

// ---- errors ----------------------------------------------------------------------------------------------

void expect_error_naming(const VoxelGrid& g, const fs::path& out, const std::string& also) {
  try {
    write_volume(g, out);
    ADD_FAILURE() << "no error for " << out;
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(out.string()), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find(also), std::string::npos) << e.what();
  }
}

TEST(VolumeWriter, ErrorsNameTheOutput) {
  const test::TempDir folder;
  const fs::path& dir = folder.path();
  expect_error_naming(small_grid(), dir / "g.binvox", "5x4x3");
  expect_error_naming(make_grid(spec_of({300, 1, 1}), {{299, 0, 0}}), dir / "wide.vox", "300 along x");
  expect_error_naming(make_grid(spec_of({1, 2, 257}), {{0, 0, 0}}), dir / "tall.vox", "257 along z");
  expect_error_naming(small_grid(), dir / "g.raw", ".nrrd, .vti, .binvox, .vox");
  expect_error_naming(small_grid(), dir / "noext", "no extension");
  expect_error_naming(small_grid(), dir / "missing" / "g.nrrd", (dir / "missing").string());
  expect_error_naming(small_grid(), dir / "missing" / "g.vti", "does not exist");
  fs::create_directory(dir / "taken.vox");
  expect_error_naming(small_grid(), dir / "taken.vox", "folder");
  EXPECT_EQ(listing(dir), std::set<std::string>{"taken.vox"});  // nothing half-written
}

TEST(VolumeWriter, FullDiskNamesTheFile) {
  // A file size limit makes write() fail with EFBIG part way through, as a full disk would.
  const test::TempDir folder;
  const fs::path& dir = folder.path();
  const VoxelGrid g = make_grid(spec_of({128, 128, 80}), {{1, 2, 3}});
  rlimit old{};
  ASSERT_EQ(::getrlimit(RLIMIT_FSIZE, &old), 0);
  const auto old_handler = ::signal(SIGXFSZ, SIG_IGN);
  rlimit small = old;
  small.rlim_cur = 100000;
  ASSERT_EQ(::setrlimit(RLIMIT_FSIZE, &small), 0);
  expect_error_naming(g, dir / "g.vti", "write failed");
  expect_error_naming(g, dir / "g.nrrd", "write failed");
  ::setrlimit(RLIMIT_FSIZE, &old);
  ::signal(SIGXFSZ, old_handler);
  EXPECT_TRUE(listing(dir).empty());  // the temporary files are gone
}

TEST(VolumeWriter, WriteFailureNamesTheFile) {
  if (::geteuid() == 0) GTEST_SKIP() << "root ignores folder permissions";
  const test::TempDir folder;
  const fs::path& dir = folder.path();
  fs::permissions(dir, fs::perms::owner_read | fs::perms::owner_exec);
  expect_error_naming(small_grid(), dir / "g.nrrd", "cannot create");
  fs::permissions(dir, fs::perms::owner_all);
}

}  // namespace
}  // namespace voxr
