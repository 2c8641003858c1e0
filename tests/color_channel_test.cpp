// The color channel: exact colours on small meshes built here (vertex colours, a 2x2 texture, a factor, a
// colourless soup appended), every attribute-producing method and rule against the CPU reference bit for
// bit, determinism under a permutation of the triangles, the .vox palette (median cut), the writers and the
// sparse grid carrying the channel.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <numeric>
#include <random>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "cli_support.h"
#include "grid/sparse_voxel_grid.h"
#include "io/color_palette.h"
#include "io/volume_writer.h"
#include "test_support.h"
#include "util/error.h"
#include "voxelize/reference_voxelizer.h"
#include "voxelize/triangle_splitter.h"
#include "voxelize/voxelizer.h"

namespace voxr {
namespace {

using test::slurp;

namespace fs = std::filesystem;

constexpr uint32_t rgba(uint32_t r, uint32_t g, uint32_t b, uint32_t a = 255) {
  return r | (g << 8) | (b << 16) | (a << 24);
}

// The colour of voxel (i, j, k), or ~0 when it is not set.
uint32_t color_at(const VoxelGrid& g, uint32_t i, uint32_t j, uint32_t k) {
  const uint64_t want = g.spec.linear_index(i, j, k);
  uint32_t out = ~0u;
  g.for_each_set([&](uint64_t linear, uint64_t rank) {
    if (linear == want) out = g.color.at(rank);
  });
  return out;
}

// A triangle in the plane z = 0.5 of a unit grid: A = (0, 0) red, B = (4, 0) green, C = (0, 4) blue.
TriangleSoup rgb_triangle() {
  TriangleSoup s;
  s.positions.push_back({0.0f, 0.0f, 0.5f, 1.0f});
  s.positions.push_back({4.0f, 0.0f, 0.5f, 1.0f});
  s.positions.push_back({0.0f, 4.0f, 0.5f, 1.0f});
  s.triangles.push_back({0, 1, 2, 0});
  s.colors.vertex_rgba = {rgba(255, 0, 0), rgba(0, 255, 0), rgba(0, 0, 255)};
  return s;
}

// The square [0, 4]^2 at z = 0.5, diagonal (4, 0)-(0, 4), uv = (x, y) / 4 + offset, one look.
TriangleSoup textured_quad(glm::vec2 offset, SurfaceLook look, SoupTexture texture) {
  TriangleSoup s;
  const glm::vec2 corners[4] = {{0, 0}, {4, 0}, {0, 4}, {4, 4}};
  for (const glm::vec2& c : corners) {
    s.positions.push_back({c.x, c.y, 0.5f, 1.0f});
    s.colors.vertex_uv.push_back(c / 4.0f + offset);
  }
  s.triangles.push_back({0, 1, 2, 0});
  s.triangles.push_back({1, 3, 2, 0});
  s.colors.looks = {look};
  s.colors.textures = {std::move(texture)};
  return s;
}

// Texels: row 0 is the top of the image (v = 1).
SoupTexture two_by_two() {
  SoupTexture t;
  t.width = t.height = 2;
  t.texels = {rgba(10, 20, 30), rgba(40, 50, 60),         // top: (u < 1/2, v > 1/2), (u > 1/2, v > 1/2)
              rgba(100, 110, 120), rgba(200, 210, 220)};  // bottom
  t.source = "two_by_two";
  return t;
}

VoxelGrid run_device(const TriangleSoup& soup, const GridSpec& grid, const char* channels,
                     VoxelizeMethod method = VoxelizeMethod::kHybrid,
                     RasterMode mode = RasterMode::kConservative) {
  Voxelizer voxelizer(test::runtime());
  VoxelizeOptions options;
  options.method = method;
  options.mode = mode;
  options.channels = ChannelSet::parse(channels);
  return voxelizer.run(soup, grid, options);
}

TEST(ColorChannel, VertexColoursOfOneTriangleByHand) {
  const TriangleSoup soup = rgb_triangle();
  const GridSpec grid = test::unit_grid({5, 5, 1});
  const VoxelGrid g = run_device(soup, grid, "color");
  const VoxelGrid ref = reference_voxelize(soup, grid, RasterMode::kConservative, ChannelSet::parse("color"));
  EXPECT_EQ(test::compare_grids(ref, g), "");
  // Centre (0.5, 0.5) lies on the triangle: weights B = C = 1/8 -> 8192, A = 49152 (of 65536);
  // R = (49152 * 255 + 32768) >> 16 = 191, G = B = (8192 * 255 + 32768) >> 16 = 32.
  EXPECT_EQ(color_at(g, 0, 0, 0), rgba(191, 32, 32));
  // (1.5, 1.5): A = 16384, B = C = 24576 -> 64, 96, 96.
  EXPECT_EQ(color_at(g, 1, 1, 0), rgba(64, 96, 96));
  // (3.5, 1.5) is off the triangle: the closest point is (3, 1) on edge BC, B = 3/4, C = 1/4 -> 0, 191, 64.
  EXPECT_EQ(color_at(g, 3, 1, 0), rgba(0, 191, 64));
  // (0.5, 3.5) lies on edge BC (x + y = 4): B = 1/8, C = 7/8 -> 0, 32, (57344 * 255 + 32768) >> 16 = 223.
  EXPECT_EQ(color_at(g, 0, 3, 0), rgba(0, 32, 223));
  EXPECT_EQ(color_at(g, 4, 4, 0), ~0u);  // not touched
}

TEST(ColorChannel, TexturedQuadSamplesTheNearestTexelWithWrapAround) {
  const SurfaceLook white{0xffffffffu, 0};  // texture 0
  const GridSpec grid = test::unit_grid({4, 4, 1});
  const TriangleSoup soup = textured_quad({0.0f, 0.0f}, white, two_by_two());
  const VoxelGrid g = run_device(soup, grid, "count,color");
  const VoxelGrid ref =
      reference_voxelize(soup, grid, RasterMode::kConservative, ChannelSet::parse("count,color"));
  EXPECT_EQ(test::compare_grids(ref, g), "");
  // (0.5, 0.5): uv (1/8, 1/8) -> texel (0, bottom row); only the lower triangle touches the voxel.
  EXPECT_EQ(color_at(g, 0, 0, 0), rgba(100, 110, 120));
  EXPECT_EQ(color_at(g, 3, 0, 0), rgba(200, 210, 220));
  EXPECT_EQ(color_at(g, 0, 3, 0), rgba(10, 20, 30));
  EXPECT_EQ(color_at(g, 3, 3, 0), rgba(40, 50, 60));
  // GL_REPEAT: the same coordinates shifted by whole periods give the same colours.
  const VoxelGrid shifted =
      run_device(textured_quad({1.0f, -2.0f}, white, two_by_two()), grid, "count,color");
  EXPECT_EQ(shifted.color, g.color);
  // A factor multiplies: (128 * 100 * 255 + 32512) / 65025 = 50, (128 * 255 * 255 + 32512) / 65025 = 128.
  const TriangleSoup tinted = textured_quad({0.0f, 0.0f}, SurfaceLook{rgba(128, 255, 255), 0}, two_by_two());
  const VoxelGrid t = run_device(tinted, grid, "color");
  EXPECT_EQ(color_at(t, 0, 0, 0), rgba(50, 110, 120));
  EXPECT_EQ(test::compare_grids(
                reference_voxelize(tinted, grid, RasterMode::kConservative, ChannelSet::parse("color")), t),
            "");
}

TEST(ColorChannel, FactorOnlyAndColourlessMeshes) {
  TriangleSoup soup = test::box_soup(glm::vec3(0.5f), glm::vec3(3.5f));
  const GridSpec grid = test::unit_grid({4, 4, 4});
  // No colours at all: white.
  const VoxelGrid white = run_device(soup, grid, "color");
  ASSERT_GT(white.voxels_set, 0u);
  EXPECT_EQ(std::set<uint32_t>(white.color.begin(), white.color.end()), std::set<uint32_t>{0xffffffffu});
  // A look's factor alone (no UVs, no vertex colours): every voxel has it exactly.
  soup.colors.looks = {SurfaceLook{rgba(51, 102, 153, 204), -1}};
  const VoxelGrid factor = run_device(soup, grid, "color");
  EXPECT_EQ(std::set<uint32_t>(factor.color.begin(), factor.color.end()),
            std::set<uint32_t>{rgba(51, 102, 153, 204)});
}

TEST(ColorChannel, AColourlessSoupAppendedStaysWhite) {
  // TriangleSoup::append does not carry colours: the appended triangles lie past the colour arrays.
  TriangleSoup soup = rgb_triangle();
  soup.colors.looks = {SurfaceLook{rgba(255, 255, 255, 128), -1}};
  soup.colors.triangle_look = {0};
  soup.append(test::box_soup(glm::vec3(5.5f, 0.5f, 0.5f), glm::vec3(7.5f, 2.5f, 2.5f)));
  const GridSpec grid = test::unit_grid({8, 5, 3});
  const VoxelGrid g = run_device(soup, grid, "count,normal,color");
  EXPECT_EQ(test::compare_grids(reference_voxelize(soup, grid, RasterMode::kConservative,
                                                   ChannelSet::parse("count,normal,color")),
                                g),
            "");
  EXPECT_EQ(color_at(g, 7, 2, 2), 0xffffffffu);
  EXPECT_EQ(color_at(g, 0, 0, 0), rgba(191, 32, 32, 128));
}

// Random triangles, small and large (the hybrid method's direct pass and its slice path), with vertex
// colours, UVs well outside [0, 1], per-triangle looks with and without textures.
TriangleSoup colored_soup(uint32_t seed) {
  TriangleSoup soup = test::random_soup(seed, 300, -1.0f, 1.0f, 0.08f);
  soup.append(test::random_soup(seed + 1, 30, -1.0f, 1.0f, 1.5f));
  std::mt19937 rng(seed);
  std::uniform_int_distribution<uint32_t> any;
  std::uniform_real_distribution<float> uv(-3.0f, 3.0f);
  for (size_t v = 0; v < soup.vertex_count(); ++v) {
    soup.colors.vertex_rgba.push_back(any(rng));
    soup.colors.vertex_uv.push_back({uv(rng), uv(rng)});
  }
  for (size_t t = 0; t < soup.triangle_count(); ++t) soup.colors.triangle_look.push_back(any(rng) % 4);
  SoupTexture a;
  a.width = 3;
  a.height = 5;
  SoupTexture b;
  b.width = b.height = 7;
  for (SoupTexture* tex : {&a, &b})
    for (uint32_t i = 0; i < tex->width * tex->height; ++i) tex->texels.push_back(any(rng));
  soup.colors.textures = {a, b};
  // look 3 names no texture; triangles with look index 4+ do not occur
  soup.colors.looks = {{any(rng), 0}, {0xffffffffu, 1}, {any(rng), 1}, {any(rng), -1}};
  return soup;
}

TEST(ColorChannel, EveryAttributeMethodAndRuleEqualsTheReference) {
  const TriangleSoup soup = colored_soup(41);
  const GridSpec grid = test::fitted(soup, 40);
  Voxelizer voxelizer(test::runtime());
  for (const MethodInfo& info : kMethods) {
    if (!info.attributes) continue;
    for (RasterMode mode : {RasterMode::kConservative, RasterMode::kCenter})
      for (const char* channels : {"color", "count,normal,material,color"}) {
        VoxelizeOptions options;
        options.method = info.method;
        options.mode = mode;
        options.channels = ChannelSet::parse(channels);
        VoxelizeStats stats;
        const VoxelGrid actual = voxelizer.run(soup, grid, options, &stats);
        const VoxelGrid expected = reference_voxelize(soup, grid, mode, options.channels);
        const std::string what = fmt::format("{} {} {}", info.name, raster_mode_name(mode), channels);
        EXPECT_EQ(actual.channels, options.channels) << what;
        ASSERT_EQ(actual.color.size(), actual.voxels_set) << what;
        EXPECT_EQ(test::compare_grids(expected, actual), "") << what;
        if (info.method == VoxelizeMethod::kHybrid) {
          EXPECT_GT(stats.direct_triangles, 0u) << what;
          EXPECT_LT(stats.direct_triangles, stats.triangles) << what;
        }
      }
  }
}

TEST(ColorChannel, PermutedTrianglesGiveTheSameColours) {
  const TriangleSoup soup = colored_soup(7);
  const GridSpec grid = test::fitted(soup, 48);
  TriangleSoup permuted = soup;
  std::vector<size_t> order(soup.triangle_count());
  std::iota(order.begin(), order.end(), size_t(0));
  std::shuffle(order.begin(), order.end(), std::mt19937(3));
  for (size_t t = 0; t < order.size(); ++t) {
    permuted.triangles[t] = soup.triangles[order[t]];
    permuted.colors.triangle_look[t] = soup.colors.triangle_look[order[t]];
  }
  const VoxelGrid a = run_device(soup, grid, "count,color");
  const VoxelGrid b = run_device(permuted, grid, "count,color");
  ASSERT_GT(a.voxels_set, 100u);
  EXPECT_EQ(a.occ, b.occ);
  EXPECT_EQ(a.count, b.count);
  EXPECT_EQ(a.color, b.color);
}

TEST(ColorChannel, BadTexturesAreRefusedNamingTheFile) {
  TriangleSoup soup = textured_quad({0.0f, 0.0f}, SurfaceLook{0xffffffffu, 0}, two_by_two());
  soup.colors.textures[0].texels.pop_back();
  try {
    run_device(soup, test::unit_grid({4, 4, 1}), "color");
    FAIL() << "a texture with too few texels was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("two_by_two: the texture holds 3 texels, not 2 x 2"),
              std::string::npos)
        << e.what();
  }
}

TEST(ColorChannel, TrianglesSplitForTheGridKeepTheirColours) {
  // One triangle 2100 voxels long is split for the grid; the pieces' vertices get the splitter's
  // interpolated colours, so the channel equals the reference voxelization of the pieces.
  TriangleSoup soup = rgb_triangle();
  const GridSpec grid = test::unit_grid({2100, 8, 2});
  soup.positions[1] = {2100.0f, 0.0f, 0.5f, 1.0f};
  const VoxelGrid actual = run_device(soup, grid, "color");
  ASSERT_GT(actual.voxels_set, 0u);
  uint64_t split = 0;
  const std::optional<TriangleSoup> pieces = split_oversized_triangles(soup, grid, &split);
  ASSERT_TRUE(pieces.has_value());
  EXPECT_GT(split, 0u);
  EXPECT_EQ(test::compare_grids(
                reference_voxelize(*pieces, grid, RasterMode::kConservative, ChannelSet::parse("occ,color")),
                actual),
            "");
  // Not white: the colours of the vertices reach the voxels.
  EXPECT_GT(std::set<uint32_t>(actual.color.begin(), actual.color.end()).size(), 10u);
}

// ---- palette, writers, sparse grid -----------------------------------------------------------------------

TEST(ColorPalette, FewColoursAreKeptAndManyAreCutByTheMedian) {
  const std::vector<uint32_t> few = {rgba(1, 2, 3), rgba(1, 2, 3), rgba(9, 9, 9)};
  const ColorPalette p = median_cut_palette(few, 255);
  EXPECT_EQ(p.entries, (std::vector<uint32_t>{rgba(1, 2, 3), rgba(9, 9, 9)}));
  EXPECT_EQ(p.entry_of(rgba(9, 9, 9)), 1u);
  // By hand: R = 10, 20, 200, 200 into 2 entries. R is the widest component; sorted 10, 20, 200 (weight 2):
  // the lower box takes colours until it holds half the weight (10, 20), so the entries are the rounded
  // weighted means (10 + 20 + 1) / 2 = 15 and 200.
  const std::vector<uint32_t> three = {rgba(200, 0, 0), rgba(10, 0, 0), rgba(20, 0, 0), rgba(200, 0, 0)};
  const ColorPalette q = median_cut_palette(three, 2);
  EXPECT_EQ(q.entries, (std::vector<uint32_t>{rgba(15, 0, 0), rgba(200, 0, 0)}));
  EXPECT_EQ(q.entry_of(rgba(20, 0, 0)), 0u);
  EXPECT_EQ(q.entry_of(rgba(200, 0, 0)), 1u);
  // Many colours: 255 entries, every colour near its entry, the same palette for any input order.
  std::vector<uint32_t> many;
  std::mt19937 rng(5);
  for (int i = 0; i < 5000; ++i) many.push_back(rng() | 0xff000000u);
  const ColorPalette m = median_cut_palette(many, 255);
  EXPECT_EQ(m.entries.size(), 255u);
  std::shuffle(many.begin(), many.end(), rng);
  EXPECT_EQ(median_cut_palette(many, 255).entries, m.entries);
  for (uint32_t c : many) {
    const uint32_t e = m.entries[m.entry_of(c)];
    for (int q2 = 0; q2 < 3; ++q2)
      EXPECT_LE(std::abs(int((c >> (8 * q2)) & 255) - int((e >> (8 * q2)) & 255)), 128) << std::hex << c;
  }
}

TEST(ColorChannel, WritersAndTheSparseGridCarryIt) {
  const TriangleSoup soup = rgb_triangle();
  const VoxelGrid g = run_device(soup, test::unit_grid({5, 5, 1}), "count,color");
  ASSERT_EQ(g.color.size(), g.voxels_set);
  // Sparse bricks and back.
  const VoxelGrid back = to_dense(to_sparse(g));
  EXPECT_EQ(back.color, g.color);
  EXPECT_EQ(to_sparse(g).color.size(), g.voxels_set);

  const fs::path dir = fs::temp_directory_path() / fmt::format("voxr_color_{}", getpid());
  fs::create_directories(dir);
  // .vti: a UInt8 array of 4 components.
  write_volume(g, dir / "g.vti");
  const std::string vti = slurp(dir / "g.vti");
  const size_t array = vti.find("<DataArray type=\"UInt8\" Name=\"color\" NumberOfComponents=\"4\"");
  ASSERT_NE(array, std::string::npos);
  // Its appended block: a 64-bit byte count, then voxel (0, 0, 0)'s RGBA.
  const size_t offset_at = vti.find("offset=\"", array) + 8;
  const size_t offset = std::stoul(vti.substr(offset_at, vti.find('"', offset_at) - offset_at));
  const size_t block = vti.find("<AppendedData encoding=\"raw\">\n   _") + 34 + offset;
  ASSERT_LE(block + 12, vti.size());
  uint64_t bytes = 0;
  std::memcpy(&bytes, vti.data() + block, 8);
  EXPECT_EQ(bytes, 4u * 25u);
  EXPECT_EQ(vti.substr(block + 8, 4), std::string("\xbf\x20\x20\xff", 4));
  // .nrrd: a sibling uchar 4-vector file whose voxel (0, 0, 0) holds the colour.
  write_volume(g, dir / "g.nrrd");
  const std::string nrrd = slurp(dir / "g.color.nrrd");
  EXPECT_NE(nrrd.find("type: uint8\n"), std::string::npos);
  EXPECT_NE(nrrd.find("sizes: 4 5 5 1\n"), std::string::npos);
  EXPECT_NE(nrrd.find("kinds: 4-vector domain domain domain\n"), std::string::npos);
  const std::string data = nrrd.substr(nrrd.find("\n\n") + 2);
  ASSERT_EQ(data.size(), 4u * 25u);
  EXPECT_EQ(data.substr(0, 4), std::string("\xbf\x20\x20\xff", 4));
  // .vox: the palette holds the voxels' colours (fewer than 255 distinct) and each voxel its own.
  write_volume(g, dir / "g.vox");
  const std::string vox = slurp(dir / "g.vox");
  const size_t xyzi = vox.find("XYZI"), palette = vox.find("RGBA");
  ASSERT_NE(xyzi, std::string::npos);
  ASSERT_NE(palette, std::string::npos);
  const ColorPalette p = median_cut_palette(g.color, 255);
  int32_t n = 0;
  std::memcpy(&n, vox.data() + xyzi + 12, 4);
  ASSERT_EQ(uint64_t(n), g.voxels_set);
  std::set<uint32_t> written;
  for (int32_t v = 0; v < n; ++v) {
    const uint8_t index = uint8_t(vox[xyzi + 16 + 4 * size_t(v) + 3]);
    ASSERT_GE(index, 1);
    uint32_t entry = 0;
    std::memcpy(&entry, vox.data() + palette + 12 + 4 * (index - 1), 4);
    written.insert(entry);
  }
  EXPECT_EQ(written, std::set<uint32_t>(g.color.begin(), g.color.end()));
  EXPECT_EQ(p.entries.size(), written.size());
  fs::remove_all(dir);
}

}  // namespace
}  // namespace voxr
