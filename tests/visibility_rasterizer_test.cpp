// The kernel rasterizer (render/visibility_rasterizer.h): visibility words equal to the CPU reference bit for
// bit, shared edges covering every pixel centre exactly once (the top-left rule), huge triangles split into
// many work items, near-plane clipping, batching, determinism, and the resolve's surface samples.
#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>

#include <fmt/format.h>

#include "core/generators.h"
#include "render/reference_raster.h"
#include "render/vertex_normals.h"
#include "render/visibility_rasterizer.h"
#include "test_support.h"

namespace voxr {
namespace {

constexpr uint64_t kEmpty = ~uint64_t(0);
constexpr uint64_t kCanary = 0xa5a5a5a5a5a5a5a5ull;
constexpr size_t kCanaryWords = 512;

CameraFrame look_at(glm::vec3 eye, glm::vec3 target, uint32_t width, uint32_t height, float fov_deg = 45.0f,
                    float near_plane = 0.05f, float far_plane = 50.0f) {
  CameraFrame f;
  f.eye = eye;
  f.forward = glm::normalize(target - eye);
  f.right = glm::normalize(glm::cross(f.forward, glm::vec3(0, 1, 0)));
  f.up = glm::cross(f.right, f.forward);
  f.tan_half_fov_y = std::tan(glm::radians(fov_deg) * 0.5f);
  f.width = width;
  f.height = height;
  f.near_plane = near_plane;
  f.far_plane = far_plane;
  return f;
}

// An orthographic target whose world x, y are image pixel coordinates (x right, y down), depth z in [0, 1].
RasterTarget pixel_ortho(uint32_t width, uint32_t height) {
  RasterTarget t;
  glm::mat4 m(0.0f);
  m[0][0] = 2.0f / float(width);
  m[3][0] = -1.0f;
  m[1][1] = -2.0f / float(height);
  m[3][1] = 1.0f;
  m[2][2] = 1.0f;
  m[3][3] = 1.0f;
  t.view_projection = m;
  t.width = width;
  t.height = height;
  return t;
}

std::vector<RenderMaterial> materials(std::initializer_list<uint32_t> kinds) {
  std::vector<RenderMaterial> out;
  for (uint32_t k : kinds) {
    RenderMaterial m{};
    m.kind = k;
    out.push_back(m);
  }
  return out;
}

const std::vector<RenderMaterial> kOpaque5 = materials({0, 0, 0, 0, 0});

cl::Buffer upload_materials(ClRuntime& cl, const std::vector<RenderMaterial>& mats) {
  const uint64_t bytes = std::max<uint64_t>(mats.size(), 1) * sizeof(RenderMaterial);
  cl::Buffer b = cl.buffer(bytes, "test materials");
  if (!mats.empty()) cl.upload(b, mats.data(), mats.size() * sizeof(RenderMaterial), "upload materials");
  return b;
}

// Coverage counts (checks of the tie rule) through the test kernel kernels/test/raster_count.cl: 2 * width *
// height uint, per pixel the front then the back primitives (VOXR_PRIM_BACK) that cover its centre.
void count_coverage(ClRuntime& cl, VisibilityRasterizer& raster, RasterBins& bins, GrowingBuffer& counts) {
  const uint32_t width = bins.width(), height = bins.height();
  const uint64_t bytes = uint64_t(width) * height * 2 * sizeof(cl_uint);
  cl::Buffer& out = counts.ensure(cl, bytes, "coverage counts");
  cl.fill_zero(out, bytes, "clear");
  cl::Kernel count = cl.kernel("raster_count.cl", "raster_count", {{"WG_SIZE", "256"}});
  raster.for_each_batch(bins, [&](const cl::Buffer& records, uint32_t n) {
    cl.launch("raster_count", count, n, 256, cl_uint(width), cl_uint(height), bins.prims(), records,
              cl_uint(n), out);
  });
}

struct DeviceRaster {
  std::vector<uint64_t> words;
  std::vector<uint32_t> counts;  // 2 per pixel (front, back), when asked
  RasterStats stats;
};

DeviceRaster run_device(const TriangleSoup& soup, const RasterTarget& target,
                        const std::vector<RenderMaterial>& mats, bool counts = false,
                        uint64_t budget_bytes = uint64_t(128) << 20) {
  ClRuntime& cl = test::runtime();
  const DeviceMesh mesh(cl, soup);
  const cl::Buffer mat_buffer = upload_materials(cl, mats);
  VisibilityRasterizer raster(cl, budget_bytes);
  const size_t pixels = size_t(target.width) * target.height;
  // A canary after the image catches writes past its end (the buffer is already large enough, so kept).
  GrowingBuffer visibility;
  std::vector<uint64_t> canary(pixels + kCanaryWords, kCanary);
  cl.upload(visibility.ensure(cl, canary.size() * 8, "test visibility"), canary.data(), canary.size() * 8,
            "upload canary");
  DeviceRaster out;
  raster.rasterize(mesh, target, mat_buffer, uint32_t(mats.size()), visibility, &out.stats);
  cl.download(visibility.buffer, canary.data(), canary.size() * 8, "readback visibility");
  out.words.assign(canary.begin(), canary.begin() + pixels);
  for (size_t i = pixels; i < canary.size(); ++i) EXPECT_EQ(canary[i], kCanary) << "write past the image";
  if (counts) {
    RasterBins bins;
    raster.bin(mesh, target, mat_buffer, uint32_t(mats.size()), bins);
    GrowingBuffer count_buffer;
    count_coverage(cl, raster, bins, count_buffer);
    out.counts.resize(pixels * 2);
    cl.download(count_buffer.buffer, out.counts.data(), pixels * 8, "readback counts");
  }
  cl.finish();
  return out;
}

// Empty when equal; else the number of differing pixels and the first few.
std::string compare_words(const std::vector<uint64_t>& expected, const std::vector<uint64_t>& actual,
                          uint32_t width) {
  if (expected.size() != actual.size()) return "sizes differ";
  std::string report;
  size_t differences = 0;
  for (size_t i = 0; i < expected.size(); ++i)
    if (expected[i] != actual[i] && differences++ < 8)
      report +=
          fmt::format("  pixel ({}, {}): {:016x} vs {:016x}\n", i % width, i / width, expected[i], actual[i]);
  return differences ? fmt::format("{} pixels differ:\n{}", differences, report) : std::string();
}

size_t covered(const std::vector<uint64_t>& words) {
  return size_t(std::count_if(words.begin(), words.end(), [](uint64_t w) { return w != kEmpty; }));
}

void expect_matches_reference(const TriangleSoup& soup, const RasterTarget& target,
                              const std::vector<RenderMaterial>& mats, const std::string& what) {
  const ReferenceRaster ref = reference_raster(soup, target, mats);
  const DeviceRaster dev = run_device(soup, target, mats);
  EXPECT_EQ(compare_words(ref.visibility, dev.words, target.width), "") << what;
  EXPECT_EQ(dev.stats.records, ref.records) << what;
  EXPECT_GT(covered(ref.visibility), 0u) << what;
}

TEST(Visibility, MatchesReferenceOnRandomSoups) {
  for (uint32_t seed = 1; seed <= 4; ++seed) {
    // Triangles around and behind the camera: near-plane and guard-band clipping, off-screen culling.
    const TriangleSoup soup = test::random_soup(seed, 400, -3.0f, 3.0f, 1.5f);
    const CameraFrame frame =
        look_at(glm::vec3(0.2f, 0.3f, 1.5f), glm::vec3(0, 0, -1), 157, 93, 60.0f, 0.01f);
    expect_matches_reference(soup, camera_target(frame), kOpaque5, fmt::format("seed {}", seed));
  }
}

TEST(Visibility, MatchesReferenceOnSphereAndBox) {
  TriangleSoup scene = make_uv_sphere(1.0f, 24, 48);
  scene.append(make_box(glm::vec3(-2.0f, -1.5f, -2.0f), glm::vec3(2.0f, -1.0f, 2.0f)));
  const CameraFrame frame = look_at(glm::vec3(1.0f, 1.5f, 4.0f), glm::vec3(0), 200, 150);
  expect_matches_reference(scene, camera_target(frame), kOpaque5, "sphere and box");
}

TEST(Visibility, OrthographicKindMaskMatchesReference) {
  // A light's view: orthographic, only opaque casters (material 0 opaque, 1 sheet, 2 dielectric).
  TriangleSoup scene;
  scene.append(make_uv_sphere(0.8f), glm::mat4(1.0f), 0);
  scene.append(make_torus(), glm::translate(glm::mat4(1.0f), glm::vec3(0.5f, 0, 0)), 1);
  scene.append(make_box(glm::vec3(-1.5f, -1.2f, -1.5f), glm::vec3(1.5f, -1.0f, 1.5f)), glm::mat4(1.0f), 2);
  const std::vector<RenderMaterial> mats =
      materials({VOXR_MATERIAL_OPAQUE, VOXR_MATERIAL_SHEET, VOXR_MATERIAL_DIELECTRIC});
  RasterTarget target;
  target.view_projection = glm::orthoZO(-2.0f, 2.0f, -2.0f, 2.0f, 0.0f, 10.0f) *
                           glm::lookAt(glm::vec3(1, 4, 2), glm::vec3(0), glm::vec3(0, 1, 0));
  target.width = 128;
  target.height = 96;
  target.kind_mask = 1u << VOXR_MATERIAL_OPAQUE;
  expect_matches_reference(scene, target, mats, "opaque casters");
  const DeviceRaster dev = run_device(scene, target, mats);
  for (uint64_t w : dev.words)
    if (w != kEmpty) {
      ASSERT_EQ(scene.triangles[uint32_t(w)].w, 0u) << "a non-opaque triangle was drawn";
    }
  target.kind_mask = 7;
  expect_matches_reference(scene, target, mats, "every kind");
}

// Pixel-space convex hull of the projected vertices, in double.
std::vector<glm::dvec2> projected_hull(const TriangleSoup& soup, const RasterTarget& target) {
  std::vector<glm::dvec2> pts;
  const glm::dmat4 m(target.view_projection);
  for (const glm::vec4& p : soup.positions) {
    const glm::dvec4 c = m * glm::dvec4(glm::dvec3(glm::vec3(p)), 1.0);
    pts.push_back({(c.x / c.w + 1.0) * 0.5 * target.width, (1.0 - c.y / c.w) * 0.5 * target.height});
  }
  std::sort(pts.begin(), pts.end(), [](auto a, auto b) { return a.x < b.x || (a.x == b.x && a.y < b.y); });
  auto cross = [](glm::dvec2 o, glm::dvec2 a, glm::dvec2 b) {
    return (a.x - o.x) * (b.y - o.y) - (a.y - o.y) * (b.x - o.x);
  };
  std::vector<glm::dvec2> hull(2 * pts.size());
  size_t k = 0;
  for (size_t i = 0; i < pts.size(); ++i) {
    while (k >= 2 && cross(hull[k - 2], hull[k - 1], pts[i]) <= 0) --k;
    hull[k++] = pts[i];
  }
  for (size_t i = pts.size() - 1, t = k + 1; i-- > 0;) {
    while (k >= t && cross(hull[k - 2], hull[k - 1], pts[i]) <= 0) --k;
    hull[k++] = pts[i];
  }
  hull.resize(k - 1);
  return hull;  // positive orientation in (x right, y down)
}

// Signed distance of p to the hull's boundary: positive inside.
double hull_distance(const std::vector<glm::dvec2>& hull, glm::dvec2 p) {
  double d = 1e30;
  for (size_t i = 0; i < hull.size(); ++i) {
    const glm::dvec2 a = hull[i], b = hull[(i + 1) % hull.size()];
    const glm::dvec2 e = b - a;
    d = std::min(d, (e.x * (p.y - a.y) - e.y * (p.x - a.x)) / glm::length(e));
  }
  return d;
}

// Every pixel centre well inside the silhouette (the hull of a convex mesh's projection) is covered by
// exactly `front` front and `back` back primitives (or, with front + back == 1 for an open sheet, by one of
// either); well outside by none; no pixel by more. Snapping moves edges by at most 1/512 pixel.
void expect_exactly_once(const TriangleSoup& soup, const RasterTarget& target, int front, int back,
                         const std::string& what) {
  const DeviceRaster dev = run_device(soup, target, kOpaque5, true);
  const ReferenceRaster ref = reference_raster(soup, target, kOpaque5);
  EXPECT_TRUE(dev.counts == ref.counts) << what << ": device coverage counts differ from the reference";
  const std::vector<glm::dvec2> hull = projected_hull(soup, target);
  const double margin = 0.01;
  size_t inside = 0, bad = 0;
  std::string report;
  for (uint32_t y = 0; y < target.height; ++y)
    for (uint32_t x = 0; x < target.width; ++x) {
      const size_t i = size_t(y) * target.width + x;
      const int f = int(dev.counts[2 * i]), b = int(dev.counts[2 * i + 1]);
      const double d = hull_distance(hull, glm::dvec2(x + 0.5, y + 0.5));
      bool ok = f + b <= front + back && f <= std::max(front, 1) && b <= std::max(back, 1);
      if (d > margin) {
        ++inside;
        ok &= front + back == 1 ? f + b == 1 : (f == front && b == back);
      } else if (d < -margin) {
        ok &= f + b == 0;
      }
      if (!ok && bad++ < 8)
        report += fmt::format("  pixel ({}, {}): front {} back {} (hull distance {:.4f})\n", x, y, f, b, d);
    }
  EXPECT_EQ(bad, 0u) << what << ":\n" << report;
  EXPECT_GT(inside, size_t(target.width) * target.height / 20)
      << what << ": the silhouette is too small a test";
}

TEST(Visibility, SharedEdgesSubdividedPlaneAtAnAngle) {
  TriangleSoup plane = make_plane(glm::vec2(2.0f), 24);
  TriangleSoup tilted;
  tilted.append(plane, glm::rotate(glm::mat4(1.0f), 0.6f, glm::normalize(glm::vec3(1, 0.3f, 0.2f))));
  const CameraFrame frame = look_at(glm::vec3(0.3f, 1.8f, 2.2f), glm::vec3(0), 173, 131);
  expect_exactly_once(tilted, camera_target(frame), 1, 0, "tilted plane");
}

TEST(Visibility, SharedEdgesFanAroundAVertex) {
  // 13 spokes around a centre vertex placed on a pixel centre (ties at the shared vertex and along spokes).
  TriangleSoup fan;
  fan.positions.push_back(glm::vec4(40.5f, 32.5f, 0.5f, 1.0f));
  const int spokes = 13;
  for (int i = 0; i < spokes; ++i) {
    const float a = 6.2831853f * float(i) / spokes;
    fan.positions.push_back(glm::vec4(40.5f + std::round(30.0f * std::cos(a)),
                                      32.5f + std::round(26.0f * std::sin(a)), 0.5f, 1.0f));
  }
  for (uint32_t i = 0; i < uint32_t(spokes); ++i)
    fan.triangles.push_back({0, 1 + i, 1 + (i + 1) % spokes, 0});
  expect_exactly_once(fan, pixel_ortho(81, 65), 1, 0, "fan (orthographic, pixel-centre vertices)");
  // The same fan under a perspective camera, tilted.
  TriangleSoup tilted;
  tilted.append(fan, glm::rotate(glm::mat4(1.0f), 0.4f, glm::vec3(1, 0, 0)) *
                         glm::scale(glm::mat4(1.0f), glm::vec3(0.04f)) *
                         glm::translate(glm::mat4(1.0f), glm::vec3(-40.5f, -32.5f, 0)));
  const CameraFrame frame = look_at(glm::vec3(0.2f, -0.3f, 3.0f), glm::vec3(0), 160, 120);
  expect_exactly_once(tilted, camera_target(frame), 1, 0, "fan (perspective)");
}

TEST(Visibility, SharedEdgesPixelAlignedGrid) {
  // Vertices on pixel centres, so whole rows, columns and diagonals of centres lie exactly on shared edges:
  // any slip of the tie rule doubles or drops them.
  TriangleSoup grid;
  const int n = 12, step = 5;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i)
      grid.positions.push_back(glm::vec4(4.5f + float(step * i), 3.5f + float(step * j), 0.25f, 1.0f));
  for (uint32_t j = 0; j < uint32_t(n); ++j)
    for (uint32_t i = 0; i < uint32_t(n); ++i) {
      const uint32_t a = j * (n + 1) + i, b = a + 1, c = a + n + 1, d = c + 1;
      if ((i + j) % 2) {
        grid.triangles.push_back({a, b, d, 0});
        grid.triangles.push_back({a, d, c, 0});
      } else {  // the other diagonal, and clockwise: both windings are drawn
        grid.triangles.push_back({a, c, b, 0});
        grid.triangles.push_back({b, c, d, 0});
      }
    }
  const RasterTarget target = pixel_ortho(70, 66);
  const DeviceRaster dev = run_device(grid, target, kOpaque5, true);
  size_t inside = 0;
  for (uint32_t y = 0; y < target.height; ++y)
    for (uint32_t x = 0; x < target.width; ++x) {
      const size_t i = size_t(y) * target.width + x;
      const uint32_t total = dev.counts[2 * i] + dev.counts[2 * i + 1];
      // Centres on the outer boundary go to the left and top edges only.
      const bool in = x >= 4 && x < 4 + uint32_t(n * step) && y >= 3 && y < 3 + uint32_t(n * step);
      inside += in;
      ASSERT_EQ(total, in ? 1u : 0u) << "pixel (" << x << ", " << y << ")";
    }
  EXPECT_EQ(inside, size_t(n * step) * (n * step));
}

TEST(Visibility, SharedEdgesClosedSphereFromOutside) {
  const TriangleSoup sphere = make_uv_sphere(1.0f, 20, 40);
  const CameraFrame frame = look_at(glm::vec3(0.4f, 0.7f, 3.0f), glm::vec3(0), 151, 127);
  // Seen from outside, the front layer and the back layer each cover the silhouette exactly once.
  expect_exactly_once(sphere, camera_target(frame), 1, 1, "sphere");
}

TEST(Visibility, FaceCullingKeepsExactlyTheOtherFaces) {
  // A closed sphere and a box behind it: culling front faces keeps exactly the back layer's coverage,
  // culling back faces the front layer's, and both match the reference bit for bit.
  TriangleSoup scene = make_uv_sphere(1.0f, 20, 40);
  scene.append(make_box(glm::vec3(-1.5f, -1.5f, -3.0f), glm::vec3(1.5f, 1.5f, -2.0f)));
  const RasterTarget all = camera_target(look_at(glm::vec3(0.4f, 0.7f, 3.0f), glm::vec3(0), 151, 127));
  RasterTarget back_only = all, front_only = all;
  back_only.cull = FaceCull::kFront;
  front_only.cull = FaceCull::kBack;
  const DeviceRaster none = run_device(scene, all, kOpaque5, true);
  const DeviceRaster backs = run_device(scene, back_only, kOpaque5, true);
  const DeviceRaster fronts = run_device(scene, front_only, kOpaque5, true);
  size_t front_pixels = 0, back_pixels = 0, deeper = 0;
  for (size_t i = 0; i < none.words.size(); ++i) {
    ASSERT_EQ(backs.counts[2 * i], 0u) << "a front face drawn with front faces culled, pixel " << i;
    ASSERT_EQ(fronts.counts[2 * i + 1], 0u) << "a back face drawn with back faces culled, pixel " << i;
    ASSERT_EQ(backs.counts[2 * i + 1], none.counts[2 * i + 1]) << "pixel " << i;
    ASSERT_EQ(fronts.counts[2 * i], none.counts[2 * i]) << "pixel " << i;
    front_pixels += none.counts[2 * i] > 0;
    back_pixels += none.counts[2 * i + 1] > 0;
    // The unculled word is the nearer of the two layers' words.
    ASSERT_EQ(none.words[i], std::min(backs.words[i], fronts.words[i])) << "pixel " << i;
    deeper += backs.words[i] != kEmpty && backs.words[i] > fronts.words[i];
  }
  EXPECT_GT(front_pixels, size_t(all.width) * all.height / 10);
  EXPECT_GT(back_pixels, size_t(all.width) * all.height / 10);
  EXPECT_GT(deeper, back_pixels / 2) << "the back layer lies behind the front one";
  for (const RasterTarget* t : {&back_only, &front_only}) {
    const ReferenceRaster ref = reference_raster(scene, *t, kOpaque5);
    const DeviceRaster& dev = t == &back_only ? backs : fronts;
    EXPECT_EQ(compare_words(ref.visibility, dev.words, t->width), "");
    EXPECT_TRUE(ref.counts == dev.counts);
    EXPECT_EQ(ref.records, dev.stats.records);
  }
}

TEST(Visibility, HugeTriangleSplitsIntoManyWorkItems) {
  TriangleSoup soup;
  for (glm::vec2 p : {glm::vec2(-1, -1), glm::vec2(3, -1), glm::vec2(-1, 3)})
    soup.positions.push_back(glm::vec4(p, 0.5f, 1.0f));
  soup.triangles.push_back({0, 1, 2, 0});
  RasterTarget target;  // identity: the triangle covers the whole 1024 x 1024 image
  target.width = target.height = 1024;
  const DeviceRaster dev = run_device(soup, target, kOpaque5);
  EXPECT_EQ(covered(dev.words), size_t(1024) * 1024);
  EXPECT_EQ(dev.words[12345], (uint64_t(std::bit_cast<uint32_t>(0.5f)) << 32) | 0u);
  EXPECT_EQ(dev.stats.records, uint64_t(128) * 128) << "one record (work item) per 8x8 tile";
  EXPECT_EQ(dev.stats.batches, 1u);
  // A record budget of 1000 records: 17 batches, the same words.
  const DeviceRaster batched = run_device(soup, target, kOpaque5, false, 1000 * sizeof(CopyRecord));
  EXPECT_EQ(batched.stats.batches, 17u);
  EXPECT_EQ(batched.stats.records, dev.stats.records);
  EXPECT_TRUE(batched.words == dev.words);
}

TEST(Visibility, BatchedRandomSoupEqualsSingleBatch) {
  const TriangleSoup soup = test::random_soup(7, 300, -1.0f, 1.0f, 0.8f);
  const RasterTarget target = camera_target(look_at(glm::vec3(0, 0, 3), glm::vec3(0), 120, 100));
  const DeviceRaster one = run_device(soup, target, kOpaque5);
  const DeviceRaster many = run_device(soup, target, kOpaque5, false, 97 * sizeof(CopyRecord));
  EXPECT_GT(many.stats.batches, 10u);
  EXPECT_EQ(compare_words(one.words, many.words, target.width), "");
}

TEST(Visibility, EqualDepthGoesToLowerTriangle) {
  // The same triangle three times (ids 0, 1, 2), drawn in whatever order the work items run.
  TriangleSoup soup;
  for (glm::vec3 p :
       {glm::vec3(-0.8f, -0.7f, -2.0f), glm::vec3(0.9f, -0.6f, -2.5f), glm::vec3(0.0f, 0.8f, -1.5f)})
    soup.positions.push_back(glm::vec4(p, 1.0f));
  for (uint32_t k = 0; k < 3; ++k) soup.triangles.push_back({0, 1, 2, 0});
  const RasterTarget target = camera_target(look_at(glm::vec3(0), glm::vec3(0, 0, -1), 64, 64));
  const DeviceRaster dev = run_device(soup, target, kOpaque5);
  ASSERT_GT(covered(dev.words), 100u);
  for (uint64_t w : dev.words)
    if (w != kEmpty) {
      ASSERT_EQ(uint32_t(w), 0u);
    }
}

TEST(Visibility, Deterministic) {
  TriangleSoup scene = make_tree(2.0f);
  const CameraFrame frame = look_at(glm::vec3(1.5f, 1.2f, 2.0f), glm::vec3(0, 0.9f, 0), 160, 120);
  const DeviceRaster a = run_device(scene, camera_target(frame), kOpaque5);
  const DeviceRaster b = run_device(scene, camera_target(frame), kOpaque5);
  EXPECT_GT(covered(a.words), 1000u);
  EXPECT_TRUE(a.words == b.words);
}

// The resolve of one frame: samples per pixel, with the words they came from.
struct Resolved {
  std::vector<uint64_t> words;
  std::vector<SurfaceSample> samples;
};

Resolved resolve_frame(const TriangleSoup& soup, const CameraFrame& frame,
                       const std::vector<RenderMaterial>& mats) {
  ClRuntime& cl = test::runtime();
  const DeviceMesh mesh(cl, soup);
  const cl::Buffer mat_buffer = upload_materials(cl, mats);
  const cl::Buffer normals = upload_vertex_normals(cl, vertex_normals(soup));
  VisibilityRasterizer raster(cl);
  const size_t pixels = size_t(frame.width) * frame.height;
  GrowingBuffer visibility, samples;
  std::vector<uint64_t> canary(pixels * sizeof(SurfaceSample) / 8 + kCanaryWords, kCanary);
  cl.upload(samples.ensure(cl, canary.size() * 8, "test samples"), canary.data(), canary.size() * 8,
            "upload canary");
  raster.rasterize(mesh, camera_target(frame), mat_buffer, uint32_t(mats.size()), visibility);
  raster.resolve(mesh, normals, frame, visibility.buffer, samples);
  Resolved out;
  out.words.resize(pixels);
  out.samples.resize(pixels);
  cl.download(visibility.buffer, out.words.data(), pixels * 8, "readback visibility");
  cl.download(samples.buffer, canary.data(), canary.size() * 8, "readback samples");
  std::memcpy(out.samples.data(), canary.data(), pixels * sizeof(SurfaceSample));
  for (size_t i = pixels * sizeof(SurfaceSample) / 8; i < canary.size(); ++i)
    EXPECT_EQ(canary[i], kCanary) << "write past the image";
  cl.finish();
  return out;
}

glm::vec3 vec(const float (&a)[3]) {
  return glm::vec3(a[0], a[1], a[2]);
}

TEST(Visibility, NearPlaneClipsAFloorPassingBehindTheCamera) {
  // A floor triangle (y = 0) reaching far behind and to both sides of a camera 1 above it.
  TriangleSoup floor;
  const glm::vec3 corner[3] = {glm::vec3(-20, 0, 10), glm::vec3(20, 0, 10), glm::vec3(0, 0, -40)};
  for (glm::vec3 p : corner) floor.positions.push_back(glm::vec4(p, 1.0f));
  floor.triangles.push_back({0, 1, 2, 0});
  // The second near plane is so close that the clipped floor reaches beyond the guard band.
  for (float near_plane : {0.05f, 1e-5f}) {
    const CameraFrame frame =
        look_at(glm::vec3(0, 1, 0), glm::vec3(0, 0.6f, -5), 96, 72, 45.0f, near_plane, 100.0f);
    const std::string what = fmt::format("floor, near plane {}", near_plane);
    expect_matches_reference(floor, camera_target(frame), kOpaque5, what);
    const Resolved r = resolve_frame(floor, frame, kOpaque5);
    size_t hits = 0;
    for (uint32_t y = 0; y < frame.height; ++y)
      for (uint32_t x = 0; x < frame.width; ++x) {
        const size_t i = size_t(y) * frame.width + x;
        const SurfaceSample& s = r.samples[i];
        // Where the pixel's ray meets the floor, and whether that is well inside the triangle (xz
        // barycentrics).
        const glm::vec3 dir = frame.ray_direction(x + 0.5f, y + 0.5f);
        bool well_inside = false;
        if (dir.y < -1e-3f && -1.0f / dir.y < 15.0f) {
          const glm::vec3 hit = frame.eye - dir / dir.y;
          const glm::vec2 a(corner[0].x, corner[0].z), b(corner[1].x, corner[1].z),
              c(corner[2].x, corner[2].z);
          const glm::vec2 q(hit.x, hit.z);
          auto cross2 = [](glm::vec2 u, glm::vec2 v) { return u.x * v.y - u.y * v.x; };
          const float area = cross2(b - a, c - a);
          const float wa = cross2(b - q, c - q) / area, wb = cross2(c - q, a - q) / area, wc = 1.0f - wa - wb;
          well_inside = wa > 0.01f && wb > 0.01f && wc > 0.01f;
        }
        if (r.words[i] == kEmpty) {
          EXPECT_EQ(s.triangle, VOXR_NO_TRIANGLE);
          EXPECT_FALSE(well_inside) << what << ": hole at (" << x << ", " << y << ")";
          continue;
        }
        ++hits;
        ASSERT_EQ(s.triangle, 0u);
        ASSERT_LT(dir.y, 0.0f) << what << ": garbage above the horizon at (" << x << ", " << y << ")";
        const float depth = std::bit_cast<float>(uint32_t(r.words[i] >> 32));
        EXPECT_TRUE(depth >= 0.0f && depth <= 1.0f);
        const glm::vec3 p = vec(s.position);
        EXPECT_NEAR(p.y, 0.0f, 1e-4f * std::max(1.0f, s.distance)) << x << ", " << y;
        EXPECT_GT(glm::dot(p - frame.eye, frame.forward), frame.near_plane * 0.99f);
        EXPECT_TRUE(p.x >= -20.01f && p.x <= 20.01f && p.z >= -40.01f && p.z <= 10.01f) << x << ", " << y;
      }
    EXPECT_GT(hits, size_t(frame.width) * frame.height / 3) << what;
    // The bottom row sees the floor just ahead; the top row sees sky.
    for (uint32_t x = 0; x < frame.width; ++x) {
      EXPECT_NE(r.words[size_t(frame.height - 1) * frame.width + x], kEmpty) << what;
      EXPECT_EQ(r.words[x], kEmpty) << what;
    }
  }
}

TEST(Visibility, ResolveOnAKnownPlane) {
  // The plane z = -3: one quad wound towards the camera, one (vertices of its own) wound away, material 1.
  TriangleSoup soup;
  for (glm::vec2 p : {glm::vec2(-2, -2), glm::vec2(0, -2), glm::vec2(0, 2), glm::vec2(-2, 2),
                      glm::vec2(0, -2), glm::vec2(2, -2), glm::vec2(2, 2), glm::vec2(0, 2)})
    soup.positions.push_back(glm::vec4(p, -3.0f, 1.0f));
  soup.triangles = {{0, 1, 2, 0}, {0, 2, 3, 0}, {4, 6, 5, 1}, {4, 7, 6, 1}};
  const CameraFrame frame = look_at(glm::vec3(0.3f, 0.2f, 1.0f), glm::vec3(0, 0, -3), 90, 70, 50.0f);
  const Resolved r = resolve_frame(soup, frame, materials({0, 2}));
  size_t hits = 0;
  for (size_t i = 0; i < r.samples.size(); ++i) {
    const SurfaceSample& s = r.samples[i];
    if (s.triangle == VOXR_NO_TRIANGLE) continue;
    ++hits;
    ASSERT_LT(s.triangle, 4u);
    const glm::vec3 p = vec(s.position);
    EXPECT_NEAR(p.z, -3.0f, 3e-4f);
    EXPECT_NEAR(glm::length(p - frame.eye), s.distance, 1e-4f * s.distance);
    const glm::vec3 dir = frame.ray_direction(float(i % frame.width) + 0.5f, float(i / frame.width) + 0.5f);
    EXPECT_LT(glm::length(frame.eye + s.distance * dir - p), 1e-4f * s.distance);
    const float u = s.barycentric[0], v = s.barycentric[1];
    EXPECT_TRUE(u >= 0.0f && v >= 0.0f && u + v <= 1.0f + 1e-6f) << u << " " << v;
    const glm::uvec4 t = soup.triangles[s.triangle];
    const glm::vec3 from_bary = (1.0f - u - v) * glm::vec3(soup.positions[t.x]) +
                                u * glm::vec3(soup.positions[t.y]) + v * glm::vec3(soup.positions[t.z]);
    EXPECT_LT(glm::length(from_bary - p), 2e-3f);
    EXPECT_EQ(s.material, t.w);
    EXPECT_NEAR(glm::dot(vec(s.geometric_normal), glm::vec3(0, 0, 1)), 1.0f, 1e-5f);
    EXPECT_NEAR(glm::dot(vec(s.normal), glm::vec3(0, 0, 1)), 1.0f, 1e-5f);
  }
  EXPECT_GT(hits, r.samples.size() / 2);
  for (size_t i = 0; i < r.samples.size(); ++i)
    if (r.samples[i].triangle == VOXR_NO_TRIANGLE) {
      EXPECT_EQ(r.samples[i].distance, 0.0f);
      EXPECT_EQ(r.samples[i].normal[0], 0.0f);
    }
}

TEST(Visibility, ResolveNormalsFaceTheEyeAndFollowTheCreaseRule) {
  // A smooth sphere: shading normals are nearly radial. A regular tetrahedron: its vertex normals lean 70.5
  // degrees from the faces, so near the corners the crease rule falls back to the face normal.
  TriangleSoup scene = make_uv_sphere(0.7f, 24, 48);
  TriangleSoup tetra;
  for (glm::vec3 p : {glm::vec3(1, 1, 1), glm::vec3(1, -1, -1), glm::vec3(-1, 1, -1), glm::vec3(-1, -1, 1)})
    tetra.positions.push_back(glm::vec4(p * 0.5f + glm::vec3(1.6f, 0, 0), 1.0f));
  tetra.triangles = {{0, 1, 2, 1}, {0, 3, 1, 1}, {0, 2, 3, 1}, {1, 3, 2, 1}};
  scene.append(tetra);
  const CameraFrame frame = look_at(glm::vec3(0.8f, 0.6f, 3.5f), glm::vec3(0.8f, 0, 0), 160, 100);
  const Resolved r = resolve_frame(scene, frame, materials({0, 0}));
  const uint32_t sphere_tris = uint32_t(make_uv_sphere(0.7f, 24, 48).triangle_count());
  size_t sphere_hits = 0, tetra_hits = 0, creased = 0;
  for (const SurfaceSample& s : r.samples) {
    if (s.triangle == VOXR_NO_TRIANGLE) continue;
    const glm::vec3 n = vec(s.normal), ng = vec(s.geometric_normal), p = vec(s.position);
    const glm::vec3 to_eye = glm::normalize(frame.eye - p);
    EXPECT_NEAR(glm::length(n), 1.0f, 1e-5f);
    EXPECT_NEAR(glm::length(ng), 1.0f, 1e-5f);
    EXPECT_GE(glm::dot(n, to_eye), 0.0f);
    EXPECT_GE(glm::dot(ng, to_eye), 0.0f);
    EXPECT_GE(glm::dot(n, ng), VOXR_CREASE_COS - 1e-5f);
    if (s.triangle < sphere_tris) {
      ++sphere_hits;
      EXPECT_GT(glm::dot(n, glm::normalize(p)), 0.995f);
    } else {
      ++tetra_hits;
      creased += n == ng;
    }
  }
  EXPECT_GT(sphere_hits, 1000u);
  EXPECT_GT(tetra_hits, 300u);
  EXPECT_GT(creased, 10u);
  EXPECT_LT(creased, tetra_hits);
}

}  // namespace
}  // namespace voxr
