// The Voxelizer as one interface: every method and every subset of channels against the CPU reference, the
// surface and the solid fill in one call, the grid kept on the device between frames, and conservative
// mode as a proven superset of the exact overlap set of the input triangles (rotated meshes and soups).
#include <gtest/gtest.h>

#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "core/generators.h"
#include "core/mesh_loader.h"
#include "test_support.h"
#include "voxelize/reference_inside.h"
#include "voxelize/reference_overlap.h"
#include "voxelize/reference_voxelizer.h"
#include "voxelize/snapped_triangle.h"
#include "voxelize/voxelizer.h"

namespace voxr {
namespace {

// Small and large triangles together: the hybrid method's direct pass and its slice path both run.
TriangleSoup mixed_soup() {
  TriangleSoup soup = test::random_soup(31, 300, -1.0f, 1.0f, 0.08f);
  soup.append(test::random_soup(32, 30, -1.0f, 1.0f, 1.5f));
  soup.append(make_torus(0.6f, 0.2f), glm::mat4(1.0f), 3);
  return soup;
}

// Channel subsets of count, normal, material (occ always there).
std::vector<ChannelSet> every_channel_subset() {
  const Channel sparse[] = {Channel::kCount, Channel::kNormal, Channel::kMaterial};
  std::vector<ChannelSet> sets;
  for (uint32_t mask = 0; mask < 8; ++mask) {
    ChannelSet set;
    for (int b = 0; b < 3; ++b)
      if (mask & (1u << b)) set.add(sparse[b]);
    sets.push_back(set);
  }
  return sets;
}

TEST(Voxelizer, EveryMethodModeAndChannelSubsetEqualsTheReference) {
  const TriangleSoup soup = mixed_soup();
  const GridSpec grid = test::fitted(soup, 40);
  Voxelizer voxelizer(test::runtime());
  for (VoxelizeMethod method : {VoxelizeMethod::kHybrid, VoxelizeMethod::kSlice, VoxelizeMethod::kGrid})
    for (RasterMode mode : {RasterMode::kConservative, RasterMode::kCenter})
      for (const ChannelSet& channels : every_channel_subset()) {
        VoxelizeOptions options;
        options.method = method;
        options.mode = mode;
        options.channels = channels;
        VoxelizeStats stats;
        const VoxelGrid actual = voxelizer.run(soup, grid, options, &stats);
        const VoxelGrid expected = reference_voxelize(soup, grid, mode, channels);
        const std::string what =
            fmt::format("{} {} {}", method_info(method).name, raster_mode_name(mode), channels.to_string());
        EXPECT_EQ(actual.channels, channels) << what;
        EXPECT_EQ(test::compare_grids(expected, actual), "") << what;
        EXPECT_EQ(stats.voxels_set, expected.voxels_set) << what;
        if (method == VoxelizeMethod::kHybrid) {
          EXPECT_GT(stats.direct_triangles, 0u) << what;
          EXPECT_LT(stats.direct_triangles, stats.triangles) << what << ": no triangle took the slice path";
        }
      }
}

TEST(Voxelizer, SurfaceChannelsAndSolidFillInOneCall) {
  // --solid parity --channels occ,count,normal,material: the surface channels equal a surface-only run, the
  // inside channel equals a solid-only run, on one upload.
  TriangleSoup soup = make_torus();
  soup.append(make_box(glm::vec3(-0.3f), glm::vec3(0.3f)), glm::mat4(1.0f), 2);
  const GridSpec grid = test::fitted(soup, 48);
  Voxelizer voxelizer(test::runtime());
  VoxelizeOptions both;
  both.channels = ChannelSet::parse("occ,count,normal,material");
  for (SolidMode mode : {SolidMode::kParity, SolidMode::kLate, SolidMode::kXor, SolidMode::kFlood}) {
    both.solid = mode;
    VoxelizeStats stats;
    const VoxelGrid g = voxelizer.run(soup, grid, both, &stats);
    EXPECT_TRUE(g.channels.has(Channel::kInside));
    EXPECT_EQ(
        test::compare_grids(reference_voxelize(soup, grid, RasterMode::kConservative, both.channels), g), "")
        << solid_mode_name(mode);
    const ReferenceSolid ref = reference_solid(soup, grid, mode);
    EXPECT_EQ(compare_bits(g.inside, ref.inside).total(), 0u) << solid_mode_name(mode);
    EXPECT_EQ(g.inside_voxels, count_bits(ref.inside));
    EXPECT_EQ(stats.inside_voxels, g.inside_voxels);
    EXPECT_GT(stats.voxels_set, 0u);
    EXPECT_GT(stats.wall_ms, 0.0);
  }
}

TEST(Voxelizer, TheGridStaysOnTheDeviceFrameAfterFrame) {
  // One upload, several frames on different grids into the same DeviceVoxelGrid (buffers reused): each
  // frame's readback equals the whole job from host memory, and repeated frames are bit-identical.
  const TriangleSoup soup = mixed_soup();
  ClRuntime& cl = test::runtime();
  Voxelizer voxelizer(cl);
  VoxelizeOptions options;
  options.channels = ChannelSet::parse("occ,count,normal,material");
  voxelizer.prepare(options);
  const GridSpec big = test::fitted(soup, 56), small = test::fitted(soup, 24);
  const DeviceMesh mesh = upload_mesh(cl, soup, big, SplitCull::kGrid);
  DeviceVoxelGrid frame;
  for (const GridSpec* grid : {&big, &small, &big}) {
    VoxelizeStats stats;
    voxelizer.run(mesh, *grid, options, frame, &stats);
    EXPECT_TRUE(frame.has_rank_index);
    EXPECT_EQ(stats.upload_ms, 0.0);
    const VoxelGrid once = read_back(cl, frame);
    voxelizer.run(mesh, *grid, options, frame);
    EXPECT_EQ(test::compare_grids(once, read_back(cl, frame), 0.0f), "") << "repeat";
    EXPECT_EQ(test::compare_grids(voxelizer.run(soup, *grid, options), once, 0.0f), "") << "from the host";
  }
}

TEST(Voxelizer, AnAdoptedOccupancyArrayIsClearedBetweenRuns) {
  // On a CPU device the occupancy can be written straight into a host array; a second run into the same
  // array must not keep the first run's bits.
  ClRuntime& cl = test::runtime();
  const TriangleSoup first = test::random_soup(51, 200, -1.0f, 1.0f, 0.3f);
  const TriangleSoup second = make_torus();
  GridRequest request;
  request.bounds = Bounds{glm::vec3(-1.5f), glm::vec3(1.5f)};
  request.resolution = 40;
  const GridSpec grid = fit_grid({}, request);
  DeviceVoxelGrid frame;
  frame.spec = grid;
  BitWords host(frame.words());
  if (!cl.can_use_in_place(host.data())) GTEST_SKIP() << "the device cannot use host memory in place";
  frame.adopt_occupancy(cl, host.data(), host.size());
  Voxelizer voxelizer(cl);
  for (const TriangleSoup* soup : {&first, &second}) {
    const DeviceMesh mesh = upload_mesh(cl, *soup, grid, SplitCull::kGrid);
    voxelizer.run(mesh, grid, VoxelizeOptions{}, frame);
  }
  const VoxelGrid result = read_back(cl, frame, &host);
  frame.release_adopted();
  EXPECT_EQ(
      test::compare_grids(reference_voxelize(second, grid, RasterMode::kConservative, ChannelSet{}), result),
      "");
}

TEST(Voxelizer, OptionsThatCannotWorkAreRefused) {
  auto message = [](const VoxelizeOptions& options) {
    try {
      options.validate();
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  VoxelizeOptions slicemap;
  slicemap.method = VoxelizeMethod::kSlicemap;
  slicemap.channels = ChannelSet::parse("occ,normal");
  EXPECT_NE(message(slicemap).find("occ channel only"), std::string::npos) << message(slicemap);
  VoxelizeOptions inside;
  inside.channels = ChannelSet::parse("occ,inside");
  EXPECT_NE(message(inside).find("--solid"), std::string::npos);
  EXPECT_EQ(parse_voxelize_method("grid"), VoxelizeMethod::kGrid);
  try {
    parse_voxelize_method("octree");
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("hybrid, slice, grid, slicemap"), std::string::npos) << e.what();
  }
}

// A random orthonormal frame (the grid's axes) from a fixed seed.
glm::mat3 random_rotation(std::mt19937& rng) {
  std::normal_distribution<float> n;
  const glm::vec3 a = glm::normalize(glm::vec3(n(rng), n(rng), n(rng)));
  glm::vec3 b = glm::vec3(n(rng), n(rng), n(rng));
  b = glm::normalize(b - glm::dot(a, b) * a);
  return glm::mat3(a, b, glm::cross(a, b));
}

// Rotated grids (and so triangles at every angle to the voxels) over meshes and soups: the conservative
// set contains every voxel the input triangles touch (0 missing against the double-precision overlap test
// on the unsnapped coordinates), and its extra voxels all lie within the snap bound (they are in the exact
// set of boxes grown by twice the bound).
TEST(Voxelizer, ConservativeIsASupersetOfTheExactSetOnRotatedMeshes) {
  std::vector<std::pair<std::string, TriangleSoup>> meshes = {
      {"torus", make_torus()},
      {"sphere", make_uv_sphere(1.0f, 24, 48)},
      {"soup", test::random_soup(41, 500, -1.0f, 1.0f, 0.2f)},
      {"slivers", test::random_soup(42, 300, -1.0f, 1.0f, 0.01f)},
      {"large", test::random_soup(43, 40, -1.0f, 1.0f, 1.5f)},
  };
  if (const std::string bunny = test::mesh_path("bunny.obj"); !bunny.empty())
    meshes.push_back({"bunny", load_mesh(bunny)});
  Voxelizer voxelizer(test::runtime());
  std::mt19937 rng(7);
  uint64_t exact_total = 0, extra_total = 0;
  for (const auto& [name, soup] : meshes)
    for (int r = 0; r < 6; ++r) {
      GridSpec grid = test::fitted(soup, 96);
      grid.axes = random_rotation(rng);
      // Re-centre the rotated grid on the mesh.
      const glm::vec3 centre = 0.5f * (soup.bounds().lo + soup.bounds().hi);
      grid.origin = centre - grid.axes * (glm::vec3(grid.dims) * (0.5f * grid.voxel_size));
      const uint32_t margin = snap_margin(grid, soup.bounds());
      for (VoxelizeMethod method : {VoxelizeMethod::kHybrid, VoxelizeMethod::kSlice}) {
        VoxelizeOptions options;
        options.method = method;
        const VoxelGrid result = voxelizer.run(soup, grid, options);
        const VoxelGrid exact = reference_overlap(soup, grid);
        const VoxelGrid near = reference_overlap(soup, grid, 2.0 * margin / VOXR_SUBVOXEL + 1e-9);
        uint64_t missing = 0, extra = 0, beyond = 0;
        for (size_t w = 0; w < exact.occ.size(); ++w) {
          missing += std::popcount(exact.occ[w] & ~result.occ[w]);
          extra += std::popcount(result.occ[w] & ~exact.occ[w]);
          beyond += std::popcount(result.occ[w] & ~near.occ[w]);
        }
        const std::string what = fmt::format("{} rotation {} {}", name, r, method_info(method).name);
        ASSERT_GT(exact.voxels_set, 100u) << what;
        EXPECT_EQ(missing, 0u) << what;
        EXPECT_EQ(beyond, 0u) << what << ": extra voxels farther than the snap bound";
        exact_total += exact.voxels_set;
        extra_total += extra;
      }
    }
  std::printf("[ superset ] %llu exact voxels, %llu extra (%.3f%%) within the snap bound\n",
              (unsigned long long)exact_total, (unsigned long long)extra_total,
              100.0 * double(extra_total) / double(exact_total));
  RecordProperty("extra_voxels", std::to_string(extra_total));
}

TEST(Voxelizer, SnapMarginGrowsWithCoordinateMagnitude) {
  GridSpec grid;
  grid.dims = glm::uvec3(64);
  grid.voxel_size = 1.0f / 64.0f;
  Bounds unit{glm::vec3(0.0f), glm::vec3(1.0f)};
  EXPECT_EQ(snap_margin(grid, unit), 1u);  // half a unit plus a tiny float error
  // A survey-scale offset: float's error in the transform is many voxels; the margin follows it.
  grid.origin = glm::vec3(412345.0f, 5823456.0f, 0.0f);
  const Bounds far{grid.origin, grid.origin + glm::vec3(1.0f)};
  EXPECT_GT(snap_margin(grid, far), 256u);
}

}  // namespace
}  // namespace voxr
