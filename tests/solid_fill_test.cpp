// Solid voxelization: every mode's kernels against its own CPU reference (exact), parity against the exact
// inside test on closed meshes (bit for bit), the documented tie and boundary rules on designed boxes, and
// measured errors of every mode against the winding-number reference on meshes with holes.
#include <gtest/gtest.h>

#include <bit>

#include <cstdio>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include <fmt/format.h>

#include "core/generators.h"
#include "core/mesh_loader.h"
#include "core/mesh_topology.h"
#include "test_support.h"
#include "util/error.h"
#include "voxelize/reference_inside.h"
#include "voxelize/voxelizer.h"

namespace voxr {
namespace {

constexpr SolidMode kModes[] = {SolidMode::kXor, SolidMode::kLate, SolidMode::kParity, SolidMode::kFlood};

// The solid fill through the Voxelizer: the conservative surface in occ, the fill in inside.
class SolidRunner {
 public:
  VoxelGrid run(const TriangleSoup& soup, const GridSpec& grid, SolidMode mode,
                VoxelizeStats* stats = nullptr) {
    VoxelizeOptions options;
    options.solid = mode;
    return voxelizer_.run(soup, grid, options, stats);
  }

 private:
  Voxelizer voxelizer_{test::runtime()};
};

std::vector<uint32_t> bits_of(const GridSpec& grid, const std::vector<glm::uvec3>& voxels) {
  std::vector<uint32_t> bits(size_t((grid.voxel_count() + 31) / 32), 0u);
  for (const glm::uvec3& v : voxels) {
    const uint64_t l = grid.linear_index(v.x, v.y, v.z);
    bits[l >> 5] |= 1u << (l & 31);
  }
  return bits;
}

// Voxels of the box [lo, hi) (index ranges, half-open).
std::vector<glm::uvec3> block(glm::uvec3 lo, glm::uvec3 hi) {
  std::vector<glm::uvec3> out;
  for (uint32_t k = lo.z; k < hi.z; ++k)
    for (uint32_t j = lo.y; j < hi.y; ++j)
      for (uint32_t i = lo.x; i < hi.x; ++i) out.push_back({i, j, k});
  return out;
}

// Every undirected edge (by vertex position) used an even number of times: closed as a mod-2 chain, which is
// all that centre parity needs (orientation does not matter). Equal positions snap equally, so it stays
// closed after snapping.
bool closed(const TriangleSoup& soup) {
  using P = std::array<float, 3>;
  std::map<std::pair<P, P>, uint32_t> uses;
  for (const glm::uvec4& t : soup.triangles)
    for (int e = 0; e < 3; ++e) {
      const glm::vec4 a = soup.positions[t[e]], b = soup.positions[t[(e + 1) % 3]];
      P pa{a.x, a.y, a.z}, pb{b.x, b.y, b.z};
      if (pb < pa) std::swap(pa, pb);
      ++uses[{pa, pb}];
    }
  for (const auto& [edge, n] : uses)
    if (n % 2) return false;
  return true;
}

std::string describe(const SolidError& e) {
  return fmt::format("missing {} extra {}", e.missing, e.extra);
}

// The closed sphere with the triangle nearest each direction removed (holes of one triangle each).
TriangleSoup holed_sphere(const std::vector<glm::vec3>& directions) {
  TriangleSoup soup = make_uv_sphere(1.0f, 24, 48);
  for (const glm::vec3& d : directions) {
    size_t best = 0;
    float best_distance = 1e9f;
    for (size_t t = 0; t < soup.triangles.size(); ++t) {
      const glm::uvec4& tri = soup.triangles[t];
      const glm::vec3 c = (glm::vec3(soup.positions[tri.x]) + glm::vec3(soup.positions[tri.y]) +
                           glm::vec3(soup.positions[tri.z])) /
                          3.0f;
      const float distance = glm::length(c - glm::normalize(d));
      if (distance < best_distance) best_distance = distance, best = t;
    }
    soup.triangles.erase(soup.triangles.begin() + ptrdiff_t(best));
  }
  return soup;
}

// Three holes below the equator (z < 0, where a column that misses its lower crossing loses its interior)
// and one above.
TriangleSoup sphere_with_holes() {
  return holed_sphere(
      {{0.3f, 0.2f, -0.93f}, {-0.5f, 0.1f, -0.86f}, {0.1f, -0.6f, -0.8f}, {0.6f, 0.5f, 0.6f}});
}

void expect_kernels_equal_reference(const TriangleSoup& soup, const GridSpec& grid, const std::string& name) {
  SolidRunner solid;
  for (SolidMode mode : kModes) {
    VoxelizeStats stats;
    const VoxelGrid g = solid.run(soup, grid, mode, &stats);
    const ReferenceSolid ref = reference_solid(soup, grid, mode);
    const SolidError e = compare_bits(g.inside, ref.inside);
    EXPECT_EQ(e.total(), 0u) << name << " " << solid_mode_name(mode) << ": " << describe(e);
    EXPECT_EQ(g.inside_voxels, count_bits(ref.inside)) << name << " " << solid_mode_name(mode);
    EXPECT_EQ(stats.inside_voxels, g.inside_voxels);
    EXPECT_EQ(stats.questionable_columns, ref.questionable_columns) << name << " " << solid_mode_name(mode);
    EXPECT_EQ(stats.repair_iterations, ref.repair_iterations) << name << " " << solid_mode_name(mode);
    EXPECT_TRUE(g.channels.has(Channel::kInside));
    EXPECT_EQ(g.inside.size(), g.occ.size());
    if (grid.voxel_count() % 32) {
      EXPECT_EQ(g.inside.back() >> (grid.voxel_count() % 32), 0u) << "tail bits";
    }
  }
}

TEST(SolidFill, ParsesModeNames) {
  for (SolidMode mode : kModes) EXPECT_EQ(parse_solid_mode(solid_mode_name(mode)), mode);
  try {
    parse_solid_mode("fill");
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("'fill'"), std::string::npos) << e.what();
  }
}

TEST(SolidFill, CompareInsideCountsMissingAndExtra) {
  const GridSpec grid = test::unit_grid({5, 4, 3});
  VoxelGrid g;
  g.spec = grid;
  const std::vector<uint32_t> inside = bits_of(grid, {{0, 0, 0}, {1, 0, 0}, {4, 3, 2}});
  g.inside.assign(inside.begin(), inside.end());
  const std::vector<uint32_t> ref = bits_of(grid, {{1, 0, 0}, {2, 1, 1}, {3, 1, 1}, {4, 3, 2}});
  const SolidError e = compare_inside(g, ref);
  EXPECT_EQ(e.missing, 2u);
  EXPECT_EQ(e.extra, 1u);
  EXPECT_EQ(e.total(), 3u);
  const SolidError off_shell = compare_inside(g, ref, bits_of(grid, {{2, 1, 1}, {0, 0, 0}}));
  EXPECT_EQ(off_shell.missing, 1u);
  EXPECT_EQ(off_shell.extra, 0u);
}

TEST(SolidFill, KernelsEqualTheirReferenceOnSmallMeshes) {
  const std::vector<std::pair<std::string, TriangleSoup>> meshes = {
      {"torus", make_torus()},
      {"sphere", make_uv_sphere()},
      {"vase", make_vase()},
      {"box", make_box()},
      {"sphere with holes", sphere_with_holes()},
      // Open, self-intersecting, randomly oriented: odd columns everywhere, long repair chains.
      {"random soup", test::random_soup(7, 200, -1.0f, 1.0f, 0.4f)},
  };
  for (const auto& [name, soup] : meshes) expect_kernels_equal_reference(soup, test::fitted(soup, 30), name);
}

TEST(SolidFill, KernelsEqualTheirReferenceAcrossWords) {
  // Rows of three words (x = 70), dims not multiples of 32: word carries of the x sweep and the repair.
  const TriangleSoup torus = make_torus();
  expect_kernels_equal_reference(torus, test::fitted(torus, 70), "torus 70");
  const TriangleSoup soup = test::random_soup(8, 150, -1.0f, 1.0f, 0.6f);
  GridRequest r;
  r.dims = glm::uvec3(70, 33, 21);
  expect_kernels_equal_reference(soup, fit_grid(soup.bounds(), r), "random soup 70x33x21");
}

TEST(SolidFill, ParityEqualsExactInsideOnClosedMeshes) {
  std::vector<std::pair<std::string, TriangleSoup>> meshes = {
      {"torus", make_torus()}, {"sphere", make_uv_sphere()}, {"vase", make_vase()}, {"box", make_box()}};
  const std::string bunny = test::mesh_path("bunny.obj");
  if (!bunny.empty()) meshes.push_back({"bunny", load_mesh(bunny)});
  SolidRunner solid;
  for (const auto& [name, soup] : meshes) {
    ASSERT_TRUE(closed(soup)) << name;
    const GridSpec grid = test::fitted(soup, name == "bunny" ? 64 : 40);
    const std::vector<uint32_t> exact = reference_inside_exact(soup, grid);
    EXPECT_GT(count_bits(exact), 100u) << name;
    const VoxelGrid parity = solid.run(soup, grid, SolidMode::kParity);
    EXPECT_EQ(compare_inside(parity, exact).total(), 0u)
        << name << ": " << describe(compare_inside(parity, exact));
    // No odd column on a closed mesh: late filling is parity.
    VoxelizeStats stats;
    const VoxelGrid late = solid.run(soup, grid, SolidMode::kLate, &stats);
    EXPECT_EQ(stats.questionable_columns, 0u) << name;
    EXPECT_EQ(late.inside, parity.inside) << name;
    // xor and flood differ from the exact set only next to the surface: every voxel they get wrong meets
    // the conservative surface.
    VoxelizeStats flood_stats;
    const VoxelGrid flood = solid.run(soup, grid, SolidMode::kFlood, &flood_stats);
    const VoxelGrid xr = solid.run(soup, grid, SolidMode::kXor);
    const SolidError xor_error = compare_inside(xr, exact), flood_error = compare_inside(flood, exact);
    EXPECT_EQ(compare_inside(xr, exact, flood.occ).total(), 0u) << name;
    EXPECT_EQ(compare_inside(flood, exact, flood.occ).total(), 0u) << name;
    EXPECT_EQ(flood_error.missing, 0u) << name << ": the flood's interior holds every centre inside";
    if (name != "box") {  // the box's faces lie in the lower halves of their slabs: xor is exact there
      EXPECT_GT(xor_error.total(), 0u) << name;
    }
    EXPECT_LE(flood_stats.flood_iterations, 4u) << name;
    std::printf("[ closed   ] %-6s %ux%ux%u inside %llu | xor %s | flood %s (%llu rounds)\n", name.c_str(),
                grid.dims.x, grid.dims.y, grid.dims.z, (unsigned long long)count_bits(exact),
                describe(xor_error).c_str(), describe(flood_error).c_str(),
                (unsigned long long)flood_stats.flood_iterations);
  }
}

TEST(SolidFill, ParityEqualsExactInsideOnRotatedAndCroppedGrids) {
  SolidRunner solid;
  const TriangleSoup torus = make_torus();
  GridSpec rotated = test::fitted(torus, 36);
  const float c = std::cos(0.5f), s = std::sin(0.5f);
  rotated.axes = glm::mat3(glm::vec3(c, s, 0), glm::vec3(-s * 0.6f, c * 0.6f, 0.8f),
                           glm::vec3(s * 0.8f, -c * 0.8f, 0.6f));
  rotated.origin = glm::vec3(-1.2f, -1.6f, -0.9f);
  rotated.dims = glm::uvec3(40, 50, 45);
  // The sphere sticks out of the grid's bottom and top: crossings below the grid still flip voxel 0.
  const TriangleSoup sphere = make_uv_sphere();
  GridRequest r;
  r.bounds = Bounds{{-1.1f, -1.1f, -0.45f}, {1.1f, 1.1f, 0.55f}};
  r.resolution = 40;
  r.margin_voxels = 0.0f;
  const std::pair<const TriangleSoup*, GridSpec> cases[] = {{&torus, rotated}, {&sphere, fit_grid({}, r)}};
  for (const auto& [soup, grid] : cases) {
    const std::vector<uint32_t> exact = reference_inside_exact(*soup, grid);
    EXPECT_GT(count_bits(exact), 1000u);
    const VoxelGrid parity = solid.run(*soup, grid, SolidMode::kParity);
    EXPECT_EQ(compare_inside(parity, exact).total(), 0u) << describe(compare_inside(parity, exact));
  }
}

TEST(SolidFill, TieRulesOnVoxelCentres) {
  // Box faces through voxel centres on all six sides (voxel 0.5, centres at -1.75 + 0.5 n; faces at +-1.25,
  // the centres of voxels 1 and 6). The column rule is the perturbation (x + e, y - e^2): the low-x and
  // high-y faces keep their columns (i = 1..5, j = 2..6); along z a crossing at a centre counts as below it:
  // the bottom face's centres are inside, the top face's are not (k = 1..5).
  const TriangleSoup soup = make_box(glm::vec3(-1.25f), glm::vec3(1.25f));
  GridRequest r;
  r.bounds = Bounds{glm::vec3(-2.0f), glm::vec3(2.0f)};
  r.resolution = 8;
  const GridSpec grid = fit_grid({}, r);
  ASSERT_EQ(grid.dims, glm::uvec3(8));
  const std::vector<uint32_t> expected = bits_of(grid, block({1, 2, 1}, {6, 7, 6}));
  SolidRunner solid;
  EXPECT_EQ(compare_bits(solid.run(soup, grid, SolidMode::kParity).inside, expected).total(), 0u);
  EXPECT_EQ(compare_bits(reference_inside_exact(soup, grid), expected).total(), 0u);
  // An octahedron with its six vertices on column centres and edges through them: still exact.
  TriangleSoup octa;
  for (glm::vec3 p :
       {glm::vec3(1.25f, -0.25f, 0.25f), glm::vec3(-1.25f, -0.25f, 0.25f), glm::vec3(0.25f, 1.25f, 0.25f),
        glm::vec3(0.25f, -1.75f, 0.25f), glm::vec3(0.25f, -0.25f, 1.75f), glm::vec3(0.25f, -0.25f, -1.25f)})
    octa.positions.push_back(glm::vec4(p, 1.0f));
  for (glm::uvec3 f : {glm::uvec3(0, 2, 4), glm::uvec3(2, 1, 4), glm::uvec3(1, 3, 4), glm::uvec3(3, 0, 4),
                       glm::uvec3(2, 0, 5), glm::uvec3(1, 2, 5), glm::uvec3(3, 1, 5), glm::uvec3(0, 3, 5)})
    octa.triangles.push_back({f.x, f.y, f.z, 0});
  const std::vector<uint32_t> exact = reference_inside_exact(octa, grid);
  EXPECT_GT(count_bits(exact), 10u);
  EXPECT_EQ(compare_inside(solid.run(octa, grid, SolidMode::kParity), exact).total(), 0u);
}

TEST(SolidFill, XorJudgesVoxelsAtTheTopOfTheirSlab) {
  // Columns i, j = 2..5 (16 of them). Faces at z = 1.7 and 6.8 lie in the upper halves of slabs 1 and 6: the
  // centre rule gives k = 2..6, xor k = 1..5 (one layer extra at the bottom, one missing at the top). At
  // z = 1.3 and 6.2 (lower halves) both give k = 1..5.
  const GridSpec grid = test::unit_grid({8, 8, 8});
  SolidRunner solid;
  const TriangleSoup high = make_box({2.2f, 2.2f, 1.7f}, {5.8f, 5.8f, 6.8f});
  const std::vector<uint32_t> high_exact = bits_of(grid, block({2, 2, 2}, {6, 6, 7}));
  EXPECT_EQ(compare_bits(reference_inside_exact(high, grid), high_exact).total(), 0u);
  const SolidError e = compare_inside(solid.run(high, grid, SolidMode::kXor), high_exact);
  EXPECT_EQ(e.missing, 16u);
  EXPECT_EQ(e.extra, 16u);
  const TriangleSoup low = make_box({2.2f, 2.2f, 1.3f}, {5.8f, 5.8f, 6.2f});
  const std::vector<uint32_t> low_exact = bits_of(grid, block({2, 2, 1}, {6, 6, 6}));
  EXPECT_EQ(compare_bits(reference_inside_exact(low, grid), low_exact).total(), 0u);
  EXPECT_EQ(compare_inside(solid.run(low, grid, SolidMode::kXor), low_exact).total(), 0u);
}

TEST(SolidFill, FastWindingNumberEqualsTheDirectSum) {
  const TriangleSoup soup = sphere_with_holes();
  const GridSpec grid = test::fitted(soup, 20);
  const std::vector<uint32_t> fast = reference_inside_winding(soup, grid);
  EXPECT_EQ(compare_bits(fast, reference_inside_winding_direct(soup, grid)).total(), 0u);
  EXPECT_GT(count_bits(fast), 2000u);
}

struct ModeErrors {
  SolidError all, off_surface;  // against the winding-number reference; off_surface: voxels off the shell
  VoxelizeStats stats;
};

struct HoleReport {
  uint64_t reference = 0;  // inside voxels of the winding-number reference
  std::map<SolidMode, ModeErrors> modes;
  ModeErrors& operator[](SolidMode m) { return modes[m]; }
};

HoleReport measure_holes(const TriangleSoup& soup, const GridSpec& grid, const char* name) {
  const std::vector<uint32_t> reference = reference_inside_winding(soup, grid);
  SolidRunner solid;
  HoleReport out;
  out.reference = count_bits(reference);
  std::vector<uint32_t> shell;
  for (SolidMode mode : {SolidMode::kFlood, SolidMode::kXor, SolidMode::kLate, SolidMode::kParity}) {
    ModeErrors m;
    const VoxelGrid g = solid.run(soup, grid, mode, &m.stats);
    if (mode == SolidMode::kFlood) shell.assign(g.occ.begin(), g.occ.end());  // the conservative surface
    m.all = compare_inside(g, reference);
    m.off_surface = compare_inside(g, reference, shell);
    std::printf("[ holes    ] %-17s %ux%ux%u ref %6llu | %-6s %-22s off-surface %-22s%s\n", name, grid.dims.x,
                grid.dims.y, grid.dims.z, (unsigned long long)count_bits(reference), solid_mode_name(mode),
                describe(m.all).c_str(), describe(m.off_surface).c_str(),
                mode == SolidMode::kLate
                    ? fmt::format(" questionable {}", m.stats.questionable_columns).c_str()
                    : "");
    out[mode] = m;
  }
  return out;
}

TEST(SolidFill, SphereWithSubVoxelHoles) {
  // Holes of one triangle each, narrower than a voxel at 24^3: the conservative surface stays closed.
  const TriangleSoup soup = sphere_with_holes();
  ASSERT_FALSE(closed(soup));
  auto m = measure_holes(soup, test::fitted(soup, 24), "sphere, holes");
  // Flood: a closed interior; every error is a conservative surface voxel counted inside.
  EXPECT_EQ(m[SolidMode::kFlood].off_surface.total(), 0u);
  EXPECT_EQ(m[SolidMode::kFlood].all.missing, 0u);
  // Parity and xor lose the interior of the columns through the lower holes (measured 76 missing voxels
  // off the surface, 4 extra above the upper hole).
  for (SolidMode mode : {SolidMode::kXor, SolidMode::kParity}) {
    EXPECT_GE(m[mode].off_surface.missing, 50u) << solid_mode_name(mode);
    EXPECT_GT(m[mode].off_surface.total(), m[SolidMode::kFlood].off_surface.total() + 50);
  }
  // Late filling finds the odd columns and repairs them from their neighbours (measured: 4 columns, no
  // error off the surface).
  EXPECT_GE(m[SolidMode::kLate].stats.questionable_columns, 2u);
  EXPECT_LE(m[SolidMode::kLate].off_surface.total(), 5u);
  EXPECT_LT(m[SolidMode::kLate].all.total(), m[SolidMode::kParity].all.total());
}

TEST(SolidFill, SphereWithHolesLargerThanAVoxel) {
  // At 40^3 the same holes are wider than a voxel: the flood leaks in and loses the interior, while late
  // filling still repairs the odd columns.
  const TriangleSoup soup = sphere_with_holes();
  auto m = measure_holes(soup, test::fitted(soup, 40), "sphere, holes");
  EXPECT_GT(m[SolidMode::kFlood].all.missing, m.reference / 2);
  EXPECT_LT(m[SolidMode::kLate].all.total(), 50u);
  EXPECT_GT(m[SolidMode::kParity].off_surface.missing, 200u);
}

TEST(SolidFill, SharkWithLargeHoles) {
  // mech-holes-shark has four open boundaries 0.2 to 0.75 of its size across: far wider than any voxel, so
  // the flood runs in and loses nearly all of the interior. Late filling is the closest to the winding
  // number.
  const std::string path = test::mesh_path("mech-holes-shark.off");
  if (path.empty()) GTEST_SKIP() << "mech-holes-shark.off missing: run scripts/fetch-meshes.sh";
  const TriangleSoup soup = load_mesh(path);
  ASSERT_FALSE(closed(soup));
  const GridSpec grid = test::fitted(soup, 32);
  auto m = measure_holes(soup, grid, "mech-holes-shark");
  EXPECT_GT(m[SolidMode::kFlood].all.missing, m.reference * 3 / 4);
  EXPECT_GT(m[SolidMode::kLate].stats.questionable_columns, 10u);
  EXPECT_LT(m[SolidMode::kLate].all.total(), m[SolidMode::kParity].all.total());
  EXPECT_LT(m[SolidMode::kParity].all.total(), m[SolidMode::kXor].all.total());
  EXPECT_LT(m[SolidMode::kXor].all.total(), m[SolidMode::kFlood].all.total());
}

TEST(SolidFill, StatsAndRepeatability) {
  const TriangleSoup soup = test::random_soup(9, 120, -1.0f, 1.0f, 0.5f);
  const GridSpec grid = test::fitted(soup, 24);
  SolidRunner solid;
  for (SolidMode mode : kModes) {
    VoxelizeStats a, b;
    const VoxelGrid first = solid.run(soup, grid, mode, &a);
    const VoxelGrid second = solid.run(soup, grid, mode, &b);
    EXPECT_EQ(first.inside, second.inside) << solid_mode_name(mode);
    EXPECT_EQ(a.questionable_columns, b.questionable_columns);
    EXPECT_EQ(a.repair_iterations, b.repair_iterations);
    EXPECT_EQ(a.flood_iterations, b.flood_iterations);
    EXPECT_GT(a.kernels_ms, 0.0);
    EXPECT_EQ(a.stage_ms.count(mode == SolidMode::kFlood ? "solid flood z" : "solid cross"), 1u)
        << solid_mode_name(mode);
    EXPECT_EQ(a.flood_iterations > 0, mode == SolidMode::kFlood);
    if (mode == SolidMode::kLate) {
      EXPECT_GT(a.questionable_columns, 0u);
      EXPECT_GT(a.repair_iterations, 0u);
    }
  }
}

TEST(SolidFill, DuplicatedTrianglesFollowTheWindingNumber) {
  // Case c20's kind: a closed box with one triangle listed twice. The generalized winding number, the
  // reference, ignores the copy (inside where w >= 1/2 is the box's inside); column parity counts it and
  // flips every column through it, so the copies are dropped first (drop_duplicate_triangles, as voxr
  // voxelize does), and then parity is the reference exactly.
  TriangleSoup box = test::box_soup(glm::vec3(0.05f), glm::vec3(0.95f, 0.83f, 0.71f));
  const TriangleSoup closed = box;
  box.triangles.push_back(box.triangles[2]);
  GridRequest r;
  r.resolution = 37;
  r.bounds = WorldBox(glm::dvec3(-0.0123, -0.0234, -0.0345), glm::dvec3(1.0123, 1.0234, 1.0345));
  const GridSpec grid = fit_grid(box.bounds(), r);
  const std::vector<uint32_t> winding = reference_inside_winding_direct(box, grid);
  EXPECT_EQ(compare_bits(winding, reference_inside_exact(closed, grid)).total(), 0u);
  uint64_t inside = 0;
  for (uint32_t w : winding) inside += uint64_t(std::popcount(w));
  EXPECT_EQ(inside, 19251u);
  SolidRunner solid;
  EXPECT_GT(compare_bits(solid.run(box, grid, SolidMode::kParity).inside, winding).total(), 1000u);
  TriangleSoup deduplicated = box;
  EXPECT_EQ(drop_duplicate_triangles(deduplicated), 1u);
  EXPECT_EQ(compare_bits(solid.run(deduplicated, grid, SolidMode::kParity).inside, winding).total(), 0u);
}

}  // namespace
}  // namespace voxr
