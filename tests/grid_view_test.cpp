// kernels/common/grid_view.h, the device-side reader of a DeviceVoxelGrid: every accessor through a probe
// kernel (kernels/test/grid_view_probe.cl) against the grid read back to the host, and the voxel traversal
// against an independent double-precision DDA plus the properties any traversal must have.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "core/generators.h"
#include "grid/channel_table.h"
#include "grid/device_voxel_grid.h"
#include "test_support.h"
#include "voxelize/device_mesh.h"
#include "voxelize/voxelizer.h"

namespace voxr {
namespace {

constexpr size_t kGroup = 64;

// A torus (material 1) and a box (material 3) that cuts through its tube, so some voxels have writers of
// both materials; both closed, so parity fills them.
TriangleSoup torus_and_box() {
  TriangleSoup soup;
  soup.append(make_torus(), glm::mat4(1.0f), 1);
  soup.append(make_box(glm::vec3(0.8f, -0.25f, -0.3f), glm::vec3(1.7f, 0.25f, 0.3f)), glm::mat4(1.0f), 3);
  return soup;
}

GridSpec with_dims(const TriangleSoup& soup, glm::uvec3 dims) {
  GridRequest r;
  r.dims = dims;
  return fit_grid(soup.bounds(), r);
}

VoxelizeOptions options(const std::string& channels, bool solid) {
  VoxelizeOptions o;
  o.channels = ChannelSet::parse(channels);
  if (solid) o.solid = SolidMode::kParity;
  return o;
}

// Voxelizes on the device into `out`; nothing is read back.
void voxelize(const TriangleSoup& soup, const GridSpec& grid, const VoxelizeOptions& o,
              DeviceVoxelGrid& out) {
  ClRuntime& cl = test::runtime();
  const DeviceMesh mesh = upload_mesh(cl, soup, grid, o.solid ? SplitCull::kColumns : SplitCull::kGrid);
  Voxelizer(cl).run(mesh, grid, o, out);
}

Defines probe_defines() {
  Defines d = channel_defines();
  d.push_back({"WG_SIZE", std::to_string(kGroup)});
  return d;
}

// ---- grid_view_fetch -------------------------------------------------------------------------------------

struct Fetched {
  std::vector<uint32_t> flags, rank, count, material;
  std::vector<glm::vec3> normal;
};

// What grid_view_fetch reports for each query voxel (xyz = i, j, k).
Fetched fetch(DeviceVoxelGrid& grid, const std::vector<glm::ivec4>& queries) {
  ClRuntime& cl = test::runtime();
  const size_t n = queries.size();
  cl::Buffer query = cl.buffer(n * 16, "probe queries");
  cl.upload(query, queries.data(), n * 16, "upload queries");
  cl::Buffer flags = cl.buffer(n * 4, "probe flags"), rank = cl.buffer(n * 4, "probe rank"),
             count = cl.buffer(n * 4, "probe count"), material = cl.buffer(n * 4, "probe material"),
             normal = cl.buffer(n * 12, "probe normal");
  cl::Kernel kernel = cl.kernel("grid_view_probe.cl", "grid_view_fetch", probe_defines());
  cl.launch("grid_view_fetch", kernel, n, kGroup, grid.view_args(cl), query, cl_uint(n), flags, rank, count,
            material, normal);
  Fetched f;
  f.flags.resize(n);
  f.rank.resize(n);
  f.count.resize(n);
  f.material.resize(n);
  f.normal.resize(n);
  cl.download(flags, f.flags.data(), n * 4, "download flags");
  cl.download(rank, f.rank.data(), n * 4, "download rank");
  cl.download(count, f.count.data(), n * 4, "download count");
  cl.download(material, f.material.data(), n * 4, "download material");
  cl.download(normal, f.normal.data(), n * 12, "download normal");
  cl.finish("grid_view_fetch");
  return f;
}

// Every voxel of the grid in linear order, then a few just outside it.
std::vector<glm::ivec4> every_voxel_and_some_outside(const GridSpec& spec) {
  std::vector<glm::ivec4> q;
  q.reserve(spec.voxel_count() + 6);
  const glm::ivec3 d(spec.dims);
  for (int k = 0; k < d.z; ++k)
    for (int j = 0; j < d.y; ++j)
      for (int i = 0; i < d.x; ++i) q.push_back({i, j, k, 0});
  for (const glm::ivec3 v : {glm::ivec3(-1, 0, 0), glm::ivec3(0, -1, 0), glm::ivec3(0, 0, -1),
                             glm::ivec3(d.x, 0, 0), glm::ivec3(0, d.y, 0), glm::ivec3(d.x - 1, d.y - 1, d.z)})
    q.push_back({v, 0});
  return q;
}

// Compares the probe's answers for every_voxel_and_some_outside() with the grid read back. `with_rank`: the
// device reported ranks (the grid has a rank index). Returns the first differences, empty when equal.
std::string compare_fetch(const VoxelGrid& host, const Fetched& f, bool with_rank) {
  const uint64_t voxels = host.spec.voxel_count();
  std::vector<uint32_t> rank_of(voxels, ~0u);
  host.for_each_set([&](uint64_t linear, uint64_t r) { rank_of[linear] = uint32_t(r); });
  std::string report;
  size_t differences = 0;
  auto note = [&](uint64_t q, const std::string& what) {
    if (differences++ < 8) report += fmt::format("  query {}: {}\n", q, what);
  };
  for (uint64_t q = 0; q < f.flags.size(); ++q) {
    const bool in_grid = q < voxels;
    const bool occ = in_grid && host.occupied(q);
    const bool inside = in_grid && host.channels.has(Channel::kInside) && host.is_inside(q);
    const uint32_t flags = uint32_t(occ) | uint32_t(inside) << 1;
    if (f.flags[q] != flags) note(q, fmt::format("flags {} vs {}", flags, f.flags[q]));
    const uint32_t r = occ ? rank_of[q] : ~0u;
    const uint32_t rank = with_rank ? r : ~0u;
    if (f.rank[q] != rank) note(q, fmt::format("rank {} vs {}", rank, f.rank[q]));
    const uint32_t count = occ && !host.count.empty() ? host.count[r] : 0u;
    const uint32_t material = occ && !host.material.empty() ? host.material[r] : 0u;
    const glm::vec3 normal = occ && !host.normal.empty() ? host.normal[r] : glm::vec3(0.0f);
    if (f.count[q] != count) note(q, fmt::format("count {} vs {}", count, f.count[q]));
    if (f.material[q] != material) note(q, fmt::format("material {} vs {}", material, f.material[q]));
    const glm::vec3 dn = glm::abs(f.normal[q] - normal);
    if (std::max({dn.x, dn.y, dn.z}) > 1e-6f)
      note(q, fmt::format("normal ({}, {}, {}) vs ({}, {}, {})", normal.x, normal.y, normal.z, f.normal[q].x,
                          f.normal[q].y, f.normal[q].z));
  }
  if (differences == 0) return {};
  return fmt::format("{} differences:\n{}", differences, report);
}

TEST(GridView, FetchesEveryChannelWithoutReadback) {
  ClRuntime& cl = test::runtime();
  const TriangleSoup soup = torus_and_box();
  const GridSpec spec = test::fitted(soup, 48);
  ASSERT_FALSE(spec.dims.x == spec.dims.y && spec.dims.y == spec.dims.z) << "the test wants a non-cubic grid";
  DeviceVoxelGrid grid;
  voxelize(soup, spec, options("occ,count,normal,material", true), grid);
  ASSERT_TRUE(grid.has_rank_index);
  // The probe runs before anything is read back: the view needs only what is on the device.
  const Fetched f = fetch(grid, every_voxel_and_some_outside(spec));
  const VoxelGrid host = read_back(cl, grid);
  ASSERT_GT(host.voxels_set, 1000u);
  ASSERT_GT(host.inside_voxels, 1000u);
  EXPECT_EQ(compare_fetch(host, f, true), "");
  // The scene exercises what it should: both materials, voxels with several writers, unit normals.
  EXPECT_NE(std::find(f.material.begin(), f.material.end(), 1u), f.material.end());
  EXPECT_NE(std::find(f.material.begin(), f.material.end(), 3u), f.material.end());
  EXPECT_GT(*std::max_element(f.count.begin(), f.count.end()), 2u);
}

TEST(GridView, OccupancyOnlyGridReadsZeroForAbsentChannels) {
  ClRuntime& cl = test::runtime();
  const TriangleSoup soup = torus_and_box();
  const GridSpec spec = test::fitted(soup, 40);
  DeviceVoxelGrid grid;
  voxelize(soup, spec, options("occ", false), grid);
  EXPECT_FALSE(grid.has_rank_index) << "occupancy alone needs no rank index";
  const std::vector<glm::ivec4> queries = every_voxel_and_some_outside(spec);
  const Fetched without_rank = fetch(grid, queries);
  const VoxelGrid host = read_back(cl, grid);
  ASSERT_GT(host.voxels_set, 1000u);
  EXPECT_EQ(compare_fetch(host, without_rank, grid.has_rank_index), "");
  // On request the rank index appears and ranks follow the occupancy's set bits in linear order.
  build_rank_index(cl, grid);
  ASSERT_TRUE(grid.has_rank_index);
  EXPECT_EQ(grid.voxels_set, host.voxels_set);
  EXPECT_EQ(compare_fetch(host, fetch(grid, queries), true), "");
}

TEST(GridView, InsideWithoutSparseChannels) {
  ClRuntime& cl = test::runtime();
  const TriangleSoup soup = torus_and_box();
  const GridSpec spec = test::fitted(soup, 40);
  DeviceVoxelGrid grid;
  voxelize(soup, spec, options("occ", true), grid);
  ASSERT_TRUE(grid.channels.has(Channel::kInside));
  const Fetched f = fetch(grid, every_voxel_and_some_outside(spec));
  const VoxelGrid host = read_back(cl, grid);
  ASSERT_GT(host.inside_voxels, 1000u);
  EXPECT_EQ(compare_fetch(host, f, grid.has_rank_index), "");
}

// ---- grid_view_march -------------------------------------------------------------------------------------

// A ray in grid units, as the probe reads it (float) and as the reference reads the same values (double).
struct Ray {
  glm::vec3 origin, dir;
};

// One ray's walk as the device reported it.
struct Walk {
  std::vector<glm::ivec4> voxels;  // xyz voxel, w axis crossed to enter it (-1 first)
  std::vector<float> t;            // ray parameter where each voxel was entered
  std::vector<uint32_t> occupied;
  bool left = false;  // ended by leaving the grid (not at the step limit)
};

// Every ray's walk through `grid` (grid_view_march), capped at dims.x + dims.y + dims.z voxels: more than
// a straight walk through the grid can visit, so a walk that reaches the cap has run away.
std::vector<Walk> march(DeviceVoxelGrid& grid, const std::vector<Ray>& rays) {
  ClRuntime& cl = test::runtime();
  const size_t n = rays.size();
  const glm::uvec3 d = grid.spec.dims;
  const uint32_t max_voxels = d.x + d.y + d.z;
  std::vector<glm::vec4> packed;
  for (const Ray& r : rays) {
    packed.push_back(glm::vec4(r.origin, 0.0f));
    packed.push_back(glm::vec4(r.dir, 0.0f));
  }
  cl::Buffer in = cl.buffer(n * 32, "probe rays");
  cl.upload(in, packed.data(), n * 32, "upload rays");
  const size_t slots = n * max_voxels;
  cl::Buffer voxels = cl.buffer(slots * 16, "probe voxels"), t = cl.buffer(slots * 4, "probe t"),
             occupied = cl.buffer(slots * 4, "probe occupied"), result = cl.buffer(n * 8, "probe result");
  cl::Kernel kernel = cl.kernel("grid_view_probe.cl", "grid_view_march", probe_defines());
  cl.launch("grid_view_march", kernel, n, kGroup, grid.view_args(cl), in, cl_uint(n), cl_uint(max_voxels),
            voxels, t, occupied, result);
  std::vector<glm::ivec4> all_voxels(slots);
  std::vector<float> all_t(slots);
  std::vector<uint32_t> all_occupied(slots);
  std::vector<glm::uvec2> results(n);
  cl.download(voxels, all_voxels.data(), slots * 16, "download voxels");
  cl.download(t, all_t.data(), slots * 4, "download t");
  cl.download(occupied, all_occupied.data(), slots * 4, "download occupied");
  cl.download(result, results.data(), n * 8, "download result");
  cl.finish("grid_view_march");
  std::vector<Walk> walks(n);
  for (size_t r = 0; r < n; ++r) {
    const size_t b = r * max_voxels, e = b + std::min(results[r].x, max_voxels);
    walks[r].voxels.assign(all_voxels.begin() + b, all_voxels.begin() + e);
    walks[r].t.assign(all_t.begin() + b, all_t.begin() + e);
    walks[r].occupied.assign(all_occupied.begin() + b, all_occupied.begin() + e);
    walks[r].left = results[r].y != 0;
  }
  return walks;
}

constexpr double kInf = std::numeric_limits<double>::infinity();
// Boundary parameters closer than this are a tie that the float walk may order either way.
constexpr double kTie = 1e-5;
// How far (grid units) an entry point may lie outside the first voxel's box.
constexpr double kEntry = 1e-4;

// The reference traversal, in double precision, written independently of grid_view.h: every boundary
// parameter is recomputed from the voxel index (no accumulated increments). Cells are half-open, as floor
// assigns them: a ray parallel to an axis lies in the grid's slab when 0 <= origin < dims on that axis.
struct RefRay {
  glm::dvec3 o, d;
  glm::ivec3 dims;

  RefRay(const Ray& r, glm::uvec3 grid_dims) : o(r.origin), d(r.dir), dims(grid_dims) {}

  // [t0, t1]: where the ray (t >= 0) is inside the grid's box; false when it misses.
  bool clip(double& t0, double& t1) const {
    t0 = 0.0;
    t1 = kInf;
    for (int a = 0; a < 3; ++a) {
      if (d[a] == 0.0) {
        if (!(o[a] >= 0.0 && o[a] < dims[a])) return false;
        continue;
      }
      double a0 = -o[a] / d[a], a1 = (dims[a] - o[a]) / d[a];
      if (a0 > a1) std::swap(a0, a1);
      t0 = std::max(t0, a0);
      t1 = std::min(t1, a1);
    }
    return t0 <= t1;
  }
  glm::dvec3 at(double t) const { return o + t * d; }
  glm::ivec3 voxel_at(double t) const {
    const glm::dvec3 p = glm::floor(at(t));
    return glm::clamp(glm::ivec3(p), glm::ivec3(0), dims - 1);
  }
  int step(int a) const { return d[a] > 0.0 ? 1 : d[a] < 0.0 ? -1 : 0; }
  // Where the ray leaves voxel v through its face across axis a; infinite when parallel to the face.
  double exit_t(glm::ivec3 v, int a) const {
    return d[a] == 0.0 ? kInf : (v[a] + (d[a] > 0.0) - o[a]) / d[a];
  }
  double first_exit(glm::ivec3 v) const { return std::min({exit_t(v, 0), exit_t(v, 1), exit_t(v, 2)}); }
  // Whether the ray's segment [t0, t1] meets voxel v's closed box grown by eps.
  bool touches(glm::ivec3 v, double t0, double t1, double eps) const {
    for (int a = 0; a < 3; ++a) {
      const double lo = v[a] - eps, hi = v[a] + 1 + eps;
      if (d[a] == 0.0) {
        if (o[a] < lo || o[a] > hi) return false;
        continue;
      }
      double a0 = (lo - o[a]) / d[a], a1 = (hi - o[a]) / d[a];
      if (a0 > a1) std::swap(a0, a1);
      t0 = std::max(t0, a0);
      t1 = std::min(t1, a1);
    }
    return t0 <= t1;
  }
  // Distance (max norm) of point p outside voxel v's closed box.
  static double outside(glm::dvec3 p, glm::ivec3 v) {
    const glm::dvec3 lo(v), below = lo - p, above = p - (lo + 1.0);
    return std::max({0.0, below.x, below.y, below.z, above.x, above.y, above.z});
  }
};

struct WalkCheck {
  std::string error;         // empty when the walk is right
  int ties = 0;              // steps that took the second of two (near-)tied faces
  double largest_gap = 0.0;  // the largest such tie gap
};

std::string describe(const Ray& r) {
  return fmt::format("ray ({:.9g}, {:.9g}, {:.9g}) + t ({:.9g}, {:.9g}, {:.9g})", r.origin.x, r.origin.y,
                     r.origin.z, r.dir.x, r.dir.y, r.dir.z);
}

// Follows the device's walk with the reference. The first voxel must be the reference's, or a neighbour
// whose box holds the entry point within kEntry; each step must cross the face the reference crosses first,
// or one whose parameter is within kTie of it; the walk must end where the first face crossed leaves the
// grid. Occupancy flags must equal the host grid's.
WalkCheck check_walk(const Ray& ray, const Walk& walk, const VoxelGrid& host) {
  const RefRay ref(ray, host.spec.dims);
  WalkCheck c;
  auto fail = [&](const std::string& what) {
    c.error = describe(ray) + ": " + what;
    return c;
  };
  double t0, t1;
  if (!ref.clip(t0, t1)) {
    if (!walk.voxels.empty())
      return fail(fmt::format("misses the grid but the device visits {} voxels", walk.voxels.size()));
    return c;
  }
  if (walk.voxels.empty())
    return fail(fmt::format("meets the grid at t = {} but the device visits nothing", t0));
  if (!walk.left) return fail("the walk hit the step limit");
  const glm::ivec3 first(walk.voxels[0]);
  if (walk.voxels[0].w != -1) return fail("the first voxel has an entry axis");
  if (first != ref.voxel_at(t0) && RefRay::outside(ref.at(t0), first) > kEntry)
    return fail(fmt::format("starts in ({}, {}, {}), the reference in ({}, {}, {})", first.x, first.y,
                            first.z, ref.voxel_at(t0).x, ref.voxel_at(t0).y, ref.voxel_at(t0).z));
  for (size_t s = 0; s < walk.voxels.size(); ++s) {
    const glm::ivec3 v(walk.voxels[s]);
    if (walk.occupied[s] != uint32_t(host.occupied(v.x, v.y, v.z)))
      return fail(fmt::format("occupancy of ({}, {}, {}) is {}", v.x, v.y, v.z, walk.occupied[s]));
    if (s == 0) continue;
    const glm::ivec3 prev(walk.voxels[s - 1]);
    const int axis = walk.voxels[s].w;
    if (axis < 0 || axis > 2 || ref.step(axis) == 0)
      return fail(fmt::format("step {} reports axis {}", s, axis));
    glm::ivec3 expected = prev;
    expected[axis] += ref.step(axis);
    if (v != expected)
      return fail(fmt::format("step {} goes from ({}, {}, {}) to ({}, {}, {}) across axis {}", s, prev.x,
                              prev.y, prev.z, v.x, v.y, v.z, axis));
    const double gap = ref.exit_t(prev, axis) - ref.first_exit(prev);
    if (gap > kTie)
      return fail(fmt::format("step {} leaves ({}, {}, {}) across axis {} at t = {}, {} after the first face",
                              s, prev.x, prev.y, prev.z, axis, ref.exit_t(prev, axis), gap));
    if (gap > 0.0) {
      ++c.ties;
      c.largest_gap = std::max(c.largest_gap, gap);
    }
  }
  const glm::ivec3 last(walk.voxels.back());
  bool leaves = false;
  for (int a = 0; a < 3; ++a) {
    const int next = last[a] + ref.step(a);
    if (ref.step(a) != 0 && (next < 0 || next >= ref.dims[a]) &&
        ref.exit_t(last, a) - ref.first_exit(last) <= kTie)
      leaves = true;
  }
  if (!leaves)
    return fail(fmt::format("the walk ends in ({}, {}, {}) after {} voxels, but the ray stays in the grid",
                            last.x, last.y, last.z, walk.voxels.size()));
  return c;
}

// The grid of the traversal tests: non-cubic, the scene's occupancy to compare the occupied flags with.
struct MarchGrid {
  DeviceVoxelGrid device;
  VoxelGrid host;
  glm::vec3 dims;
  MarchGrid() {
    const TriangleSoup soup = torus_and_box();
    voxelize(soup, with_dims(soup, {37, 23, 51}), options("occ", false), device);
    host = read_back(test::runtime(), device);
    dims = glm::vec3(device.spec.dims);
  }
};

// Rays from a box 12 voxels around the grid towards points up to 3 voxels outside it (most meet the grid,
// some miss), unit directions; every 4th starts inside the grid.
std::vector<Ray> random_rays(uint32_t seed, size_t n, glm::vec3 dims) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  auto in_box = [&](glm::vec3 lo, glm::vec3 hi) {
    return lo + (hi - lo) * glm::vec3(u(rng), u(rng), u(rng));
  };
  std::vector<Ray> rays;
  for (size_t r = 0; r < n; ++r) {
    const glm::vec3 origin =
        r % 4 == 0 ? in_box(glm::vec3(0.0f), dims) : in_box(glm::vec3(-12.0f), dims + 12.0f);
    glm::vec3 dir = in_box(glm::vec3(-3.0f), dims + 3.0f) - origin;
    if (glm::length(dir) < 1e-3f) dir = glm::vec3(1.0f, 0.5f, 0.25f);
    rays.push_back({origin, glm::normalize(dir)});
  }
  return rays;
}

TEST(GridView, MarchMatchesDoublePrecisionDda) {
  MarchGrid g;
  const std::vector<Ray> rays = random_rays(7, 4000, g.dims);
  const std::vector<Walk> walks = march(g.device, rays);
  size_t hits = 0, occupied = 0, ties = 0, failures = 0;
  double largest_gap = 0.0;
  for (size_t r = 0; r < rays.size(); ++r) {
    const WalkCheck c = check_walk(rays[r], walks[r], g.host);
    if (!c.error.empty() && failures++ < 5) ADD_FAILURE() << "ray " << r << ": " << c.error;
    hits += !walks[r].voxels.empty();
    occupied += std::count(walks[r].occupied.begin(), walks[r].occupied.end(), 1u);
    ties += size_t(c.ties);
    largest_gap = std::max(largest_gap, c.largest_gap);
  }
  EXPECT_EQ(failures, 0u);
  EXPECT_GT(hits, rays.size() * 3 / 4);
  EXPECT_LT(hits, rays.size()) << "some rays should miss";
  EXPECT_GT(occupied, 1000u) << "the rays should cross the surface";
  std::printf(
      "GridView march: %zu rays, %zu hit, %zu occupied voxels met, %zu near-ties taken in the other "
      "order (largest gap %.3g)\n",
      rays.size(), hits, occupied, ties, largest_gap);
}

TEST(GridView, MarchStepsBetweenFaceNeighboursFromTheEntryPoint) {
  MarchGrid g;
  const std::vector<Ray> rays = random_rays(11, 2000, g.dims);
  const std::vector<Walk> walks = march(g.device, rays);
  double worst_t = 0.0;
  size_t walked = 0, missed = 0;  // rays that meet the grid (the reference's clip), and the others
  for (size_t r = 0; r < rays.size(); ++r) {
    const Walk& w = walks[r];
    const RefRay ref(rays[r], g.device.spec.dims);
    double t0, t1;
    if (!ref.clip(t0, t1)) {
      ++missed;
      EXPECT_TRUE(w.voxels.empty()) << describe(rays[r]) << " misses the grid but visits " << w.voxels.size();
      continue;
    }
    // A ray that meets the grid must be walked: an empty walk is a failure, never a skip.
    ASSERT_FALSE(w.voxels.empty()) << describe(rays[r]) << " meets the grid at t = " << t0;
    ++walked;
    ASSERT_LE(RefRay::outside(ref.at(t0), glm::ivec3(w.voxels[0])), kEntry) << describe(rays[r]);
    for (size_t s = 0; s < w.voxels.size(); ++s) {
      const glm::ivec3 v(w.voxels[s]);
      ASSERT_TRUE(glm::all(glm::greaterThanEqual(v, glm::ivec3(0))) &&
                  glm::all(glm::lessThan(v, glm::ivec3(g.device.spec.dims))))
          << describe(rays[r]) << " step " << s;
      // The point where the device says it entered the voxel lies on the voxel's box (float error aside).
      worst_t = std::max(worst_t, RefRay::outside(ref.at(w.t[s]), v));
      if (s == 0) continue;
      const glm::ivec3 d = v - glm::ivec3(w.voxels[s - 1]);
      ASSERT_EQ(std::abs(d.x) + std::abs(d.y) + std::abs(d.z), 1) << describe(rays[r]) << " step " << s;
      const int axis = w.voxels[s].w;
      ASSERT_EQ(d[axis], ref.step(axis)) << describe(rays[r]) << " step " << s;
      ASSERT_GE(w.t[s], w.t[s - 1]) << describe(rays[r]) << " step " << s;
    }
  }
  EXPECT_LT(worst_t, 1e-3);
  // random_rays: 3 of 4 rays start outside and aim at points up to 3 voxels beyond the grid, every 4th
  // starts inside; most meet the grid and some miss (a test of only misses, or only hits, would prove less).
  EXPECT_EQ(walked + missed, rays.size());
  EXPECT_GT(walked, rays.size() * 3 / 4);
  EXPECT_GT(missed, 0u);
  std::printf(
      "GridView march: %zu of %zu rays walked (%zu miss); entry points lie at most %.3g outside "
      "their voxels\n",
      walked, rays.size(), missed, worst_t);
}

TEST(GridView, RaysThatMissTheGridVisitNothing) {
  MarchGrid g;
  const glm::vec3 d = g.dims;
  const std::vector<Ray> rays = {
      {{-1.0f, 5.0f, 5.0f}, {-1.0f, 0.0f, 0.0f}},      // pointing away
      {{d.x + 2.0f, 5.0f, 5.0f}, {1.0f, 0.2f, 0.0f}},  // pointing away, beyond the far face
      {{-1.0f, -0.5f, 5.0f}, {1.0f, 0.0f, 0.0f}},      // parallel, below the grid
      {{-1.0f, d.y, 5.0f}, {1.0f, 0.0f, 0.0f}},        // parallel, on the top face (outside, half-open)
      {{-1.0f, -1.0f, 5.0f}, {1.0f, -0.01f, 0.0f}},    // diverging from a corner
      {{-5.0f, -5.0f, 5.0f}, {1.0f, -1.0f, 0.0f}},     // passing the grid's edge on the outside
      {{-2.0f, 3.0f, 3.0f}, {0.0f, 0.0f, 0.0f}},       // no direction, outside
      {{d.x + 1.0f, d.y + 1.0f, d.z + 1.0f}, {1.0f, 1.0f, 1.0f}},
  };
  const std::vector<Walk> walks = march(g.device, rays);
  for (size_t r = 0; r < rays.size(); ++r) {
    EXPECT_TRUE(walks[r].voxels.empty()) << describe(rays[r]) << " visits " << walks[r].voxels.size();
    EXPECT_TRUE(walks[r].left) << describe(rays[r]);
  }
}

// Axis-parallel rays, from outside and from inside, both ways along each axis: exactly one row of voxels.
TEST(GridView, AxisParallelRaysWalkOneRow) {
  MarchGrid g;
  const glm::ivec3 dims(g.device.spec.dims);
  const glm::vec3 p(10.25f, 7.5f, 20.75f);  // a point inside the grid, off every boundary
  std::vector<Ray> rays;
  std::vector<std::vector<glm::ivec3>> expected;
  std::vector<float> entry;
  for (int a = 0; a < 3; ++a)
    for (int sign : {1, -1})
      for (bool inside : {false, true}) {
        // Negative rays get -0 in their other components: still parallel to those axes.
        glm::vec3 origin = p, dir(sign > 0 ? 0.0f : -0.0f);
        dir[a] = float(sign);
        entry.push_back(inside ? 0.0f : 3.5f);
        if (!inside) origin[a] = sign > 0 ? -3.5f : float(dims[a]) + 3.5f;
        rays.push_back({origin, dir});
        std::vector<glm::ivec3> row;
        glm::ivec3 v(glm::floor(origin));
        v[a] = inside ? int(std::floor(origin[a])) : sign > 0 ? 0 : dims[a] - 1;
        for (; v[a] >= 0 && v[a] < dims[a]; v[a] += sign) row.push_back(v);
        expected.push_back(row);
      }
  const std::vector<Walk> walks = march(g.device, rays);
  for (size_t r = 0; r < rays.size(); ++r) {
    std::vector<glm::ivec3> got;
    for (const glm::ivec4& v : walks[r].voxels) got.push_back(glm::ivec3(v));
    EXPECT_EQ(got, expected[r]) << describe(rays[r]);
    EXPECT_EQ(check_walk(rays[r], walks[r], g.host).error, "");
    if (!walks[r].voxels.empty()) {
      EXPECT_EQ(walks[r].t[0], entry[r]) << describe(rays[r]);
    }
  }
}

TEST(GridView, RaysStartingInsideBeginInTheirVoxel) {
  MarchGrid g;
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> frac(0.02f, 0.98f), dir(-1.0f, 1.0f);
  std::vector<Ray> rays;
  std::vector<glm::ivec3> start;
  for (int r = 0; r < 500; ++r) {
    const glm::ivec3 v(int(rng() % g.device.spec.dims.x), int(rng() % g.device.spec.dims.y),
                       int(rng() % g.device.spec.dims.z));
    const glm::vec3 origin = glm::vec3(v) + glm::vec3(frac(rng), frac(rng), frac(rng));
    glm::vec3 d(dir(rng), dir(rng), dir(rng));
    if (glm::length(d) < 1e-2f) d = glm::vec3(0.0f, 0.0f, 1.0f);
    rays.push_back({origin, glm::normalize(d)});
    start.push_back(v);
  }
  const std::vector<Walk> walks = march(g.device, rays);
  for (size_t r = 0; r < rays.size(); ++r) {
    ASSERT_FALSE(walks[r].voxels.empty()) << describe(rays[r]);
    EXPECT_EQ(glm::ivec3(walks[r].voxels[0]), start[r]) << describe(rays[r]);
    EXPECT_EQ(walks[r].t[0], 0.0f) << describe(rays[r]);
    EXPECT_EQ(check_walk(rays[r], walks[r], g.host).error, "");
  }
}

// Rays along grid lines and through voxel corners, where the float walk meets exact ties at every step: a
// 6-connected path of voxels whose boxes touch the line, from the voxel holding the entry point to one
// whose box holds the exit point.
TEST(GridView, RayAlongAGridLineVisitsA6ConnectedPath) {
  MarchGrid g;
  const glm::vec3 d = g.dims;
  const std::vector<Ray> rays = {
      {{-2.0f, 3.0f, 4.0f}, {1.0f, 0.0f, 0.0f}},      // along an edge line of x
      {{5.0f, 20.0f, 30.0f}, {0.0f, 0.0f, -1.0f}},    // along an edge line of z, from inside, downwards
      {{0.0f, 0.0f, 2.5f}, {1.0f, 1.0f, 0.0f}},       // through the x/y edges of a diagonal of voxels
      {{-4.0f, -4.0f, -4.0f}, {1.0f, 1.0f, 1.0f}},    // through voxel corners, from outside
      {{d.x, d.y, 20.0f}, {-1.0f, -1.0f, 0.0f}},      // from the grid's far edge back along corners
      {{10.0f, 10.0f, 10.0f}, {-1.0f, 1.0f, -1.0f}},  // corners, mixed signs, from a grid point inside
      {{0.0f, 2.5f, -3.0f}, {0.0f, 0.0f, 1.0f}},      // in the grid's low x face: its first layer
  };
  const std::vector<Walk> walks = march(g.device, rays);
  for (size_t r = 0; r < rays.size(); ++r) {
    const Walk& w = walks[r];
    const RefRay ref(rays[r], g.device.spec.dims);
    double t0, t1;
    ASSERT_TRUE(ref.clip(t0, t1)) << describe(rays[r]);
    ASSERT_FALSE(w.voxels.empty()) << describe(rays[r]);
    EXPECT_TRUE(w.left) << describe(rays[r]);
    EXPECT_LE(RefRay::outside(ref.at(t0), glm::ivec3(w.voxels.front())), kEntry) << describe(rays[r]);
    EXPECT_LE(RefRay::outside(ref.at(t1), glm::ivec3(w.voxels.back())), kEntry) << describe(rays[r]);
    for (size_t s = 0; s < w.voxels.size(); ++s) {
      const glm::ivec3 v(w.voxels[s]);
      EXPECT_TRUE(ref.touches(v, t0, t1, 1e-6)) << describe(rays[r]) << " voxel " << s;
      if (s == 0) continue;
      const glm::ivec3 step = v - glm::ivec3(w.voxels[s - 1]);
      EXPECT_EQ(std::abs(step.x) + std::abs(step.y) + std::abs(step.z), 1)
          << describe(rays[r]) << " step " << s;
    }
    EXPECT_EQ(check_walk(rays[r], w, g.host).error, "");
    // Every step along the direction: the walk spans the line inside the grid.
    const glm::ivec3 span = glm::abs(glm::ivec3(w.voxels.back()) - glm::ivec3(w.voxels.front()));
    EXPECT_EQ(size_t(span.x + span.y + span.z + 1), w.voxels.size()) << describe(rays[r]);
  }
}

}  // namespace
}  // namespace voxr
