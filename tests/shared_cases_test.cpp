// The failing inputs users reported (../shared/cases/voxelize/, README there), rebuilt here from their
// text so the suite needs no files outside the repository, each run through the voxr executable and held
// to the right result: the kinds they stand for are tested in mesh_readers_test, polygon_triangulation_test,
// far_coordinates_test and mesh_topology_test.
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cstring>
#include <sstream>
#include <string>

#include "cli_support.h"
#include "core/mesh_loader.h"
#include "grid/voxel_grid.h"
#include "voxelize/reference_overlap.h"

namespace voxr {
namespace {

namespace fs = std::filesystem;
using test::run_voxr;
using test::scratch;
using test::slurp;
using test::write_scratch_file;

// The report of `voxr voxelize ARGS --report`, after checking the run succeeded; stderr in `err`.
nlohmann::json voxelize(const std::string& args, const std::string& name, std::string* err = nullptr) {
  const fs::path report = scratch() / (name + ".json");
  const test::CliResult r = run_voxr("voxelize " + args + " -q --report " + report.string());
  EXPECT_EQ(r.code, 0) << r.err;
  if (err) *err = r.err;
  return nlohmann::json::parse(slurp(report));
}

// The data after a NRRD header (the voxels of an occupancy .nrrd).
std::string nrrd_data(const fs::path& nrrd) {
  const std::string s = slurp(nrrd);
  return s.substr(s.find("\n\n") + 2);
}

// "space origin: (x,y,z)" of a NRRD header.
glm::dvec3 nrrd_origin(const fs::path& nrrd) {
  const std::string s = slurp(nrrd);
  const size_t at = s.find("space origin: (");
  glm::dvec3 o(0.0);
  if (at == std::string::npos) return o;
  std::sscanf(s.c_str() + at, "space origin: (%lf,%lf,%lf)", &o.x, &o.y, &o.z);
  return o;
}

// A closed box [lo, hi] as OFF, 12 triangles listed as the shared cases list them; `extra` faces appended.
std::string box_off(glm::dvec3 lo, glm::dvec3 hi, const std::string& extra = "", int extra_faces = 0) {
  std::ostringstream off;
  off.precision(17);
  off << "OFF\n8 " << 12 + extra_faces << " 0\n";
  for (double z : {lo.z, hi.z})
    off << lo.x << " " << lo.y << " " << z << "\n"
        << hi.x << " " << lo.y << " " << z << "\n"
        << hi.x << " " << hi.y << " " << z << "\n"
        << lo.x << " " << hi.y << " " << z << "\n";
  off << "3 0 3 2\n3 0 2 1\n3 4 5 6\n3 4 6 7\n3 0 1 5\n3 0 5 4\n3 2 3 7\n3 2 7 6\n3 0 4 7\n3 0 7 3\n"
         "3 1 2 6\n3 1 6 5\n"
      << extra;
  return off.str();
}

TEST(SharedCases, C12BinarySTLWithTrailingBytesIsTheCube) {
  const std::string off = box_off(glm::dvec3(0.0), glm::dvec3(1.0));
  // The cube's triangles as binary STL: 80-byte header, count, 50 bytes each; then 7 bytes of padding.
  const int corners[12][3] = {{0, 3, 2}, {0, 2, 1}, {4, 5, 6}, {4, 6, 7}, {0, 1, 5}, {0, 5, 4},
                              {2, 3, 7}, {2, 7, 6}, {0, 4, 7}, {0, 7, 3}, {1, 2, 6}, {1, 6, 5}};
  auto corner = [](int i) { return glm::vec3(i == 1 || i == 2 || i == 5 || i == 6, i % 4 >= 2, i >= 4); };
  std::string stl = "binary stl" + std::string(70, ' ');
  const uint32_t n = 12;
  stl.append(reinterpret_cast<const char*>(&n), 4);
  for (const auto& t : corners) {
    const float normal[3] = {0, 0, 0};
    stl.append(reinterpret_cast<const char*>(normal), 12);
    for (int c : t) stl.append(reinterpret_cast<const char*>(&corner(c)[0]), 12);
    stl.append(2, '\0');
  }
  stl.append(7, '\0');
  const fs::path a = scratch() / "c12.nrrd", b = scratch() / "c12_off.nrrd";
  std::string err;
  const nlohmann::json ra =
      voxelize(write_scratch_file("c12.stl", stl).string() + " --res 24 -o " + a.string(), "c12", &err);
  EXPECT_NE(err.find("ignored 7 bytes after the 12 triangles"), std::string::npos) << err;
  const nlohmann::json rb =
      voxelize(write_scratch_file("c12.off", off).string() + " --res 24 -o " + b.string(), "c12_off");
  EXPECT_EQ(ra["triangles"], 12);
  EXPECT_EQ(ra["voxels_set"], rb["voxels_set"]);
  EXPECT_TRUE(nrrd_data(a) == nrrd_data(b)) << "the two volumes differ";
}

TEST(SharedCases, C13PlyFacePropertyBeforeTheIndexListIsRead) {
  const std::string header =
      "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
      "element face 4\nproperty uchar material_index\nproperty list uchar int vertex_indices\nend_header\n";
  const std::string ply = header + "0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 3 0 2 1\n3 3 0 1 3\n3 3 0 3 2\n3 3 1 2 3\n";
  const std::string off = "OFF\n4 4 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n";
  const fs::path a = scratch() / "c13.nrrd", b = scratch() / "c13_off.nrrd";
  const nlohmann::json ra =
      voxelize(write_scratch_file("c13.ply", ply).string() + " --res 16 -o " + a.string(), "c13");
  const nlohmann::json rb =
      voxelize(write_scratch_file("c13.off", off).string() + " --res 16 -o " + b.string(), "c13_off");
  EXPECT_EQ(ra["triangles"], 4);
  EXPECT_EQ(ra["voxels_set"], 680);
  EXPECT_EQ(rb["voxels_set"], 680);
  EXPECT_TRUE(nrrd_data(a) == nrrd_data(b)) << "the two volumes differ";
}

TEST(SharedCases, C18FarCubeEqualsNearCubeAndItsOriginIsExact) {
  const glm::dvec3 far(412345.0, 5823456.0, 122.0), lo(0.17, 0.28, 0.95);
  const fs::path a = scratch() / "c18_far.nrrd", b = scratch() / "c18_near.nrrd";
  // The far file's own decimal coordinates, as a survey export writes them.
  const std::string far_off =
      box_off(glm::dvec3(412345.17, 5823456.28, 122.95), glm::dvec3(412346.17, 5823457.28, 123.95));
  const nlohmann::json ra =
      voxelize(write_scratch_file("c18_far.off", far_off).string() + " --res 32 -o " + a.string(), "c18_far");
  const nlohmann::json rb = voxelize(
      write_scratch_file("c18_near.off", box_off(lo, lo + 1.0)).string() + " --res 32 -o " + b.string(),
      "c18_near");
  EXPECT_EQ(ra["voxels_set"], rb["voxels_set"]);
  // The fitted 32^3 grid holds the cube in all 32 layers per axis: its shell.
  EXPECT_EQ(rb["voxels_set"], 32 * 32 * 32 - 30 * 30 * 30);
  EXPECT_TRUE(nrrd_data(a) == nrrd_data(b)) << "the two volumes differ";
  // The header's origin is the near one moved by exactly the offset, to the input's precision (1e-9 here;
  // before, floats put it 0.22 off).
  const glm::dvec3 oa = nrrd_origin(a), ob = nrrd_origin(b);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(oa[c] - far[c], ob[c], 1e-9) << "axis " << c;
}

TEST(SharedCases, C19ConcaveCapsCoverOnlyTheirOwnArea) {
  const std::string obj =
      "v 3.0 0.0 0.0\nv 3.0 1.0 0.0\nv 1.0 1.0 0.0\nv 1.0 3.0 0.0\nv 0.0 3.0 0.0\nv 0.0 0.0 0.0\n"
      "v 3.0 0.0 1.0\nv 3.0 1.0 1.0\nv 1.0 1.0 1.0\nv 1.0 3.0 1.0\nv 0.0 3.0 1.0\nv 0.0 0.0 1.0\n"
      "f 6 5 4 3 2 1\nf 7 8 9 10 11 12\nf 1 2 8 7\nf 2 3 9 8\nf 3 4 10 9\nf 4 5 11 10\nf 5 6 12 11\nf 6 1 7 "
      "12\n";
  const fs::path mesh = write_scratch_file("c19.obj", obj);
  const nlohmann::json r = voxelize(mesh.string() + " --res 30", "c19");
  EXPECT_EQ(r["voxels_set"], 2122);
  // The exact set (double-precision triangle/box overlap of the file's triangles) on the same grid.
  const TriangleSoup soup = load_mesh(mesh);
  GridRequest request;
  request.resolution = 30;
  const GridSpec grid = fit_grid(soup.bounds(), request, soup.anchor);
  uint64_t exact = 0;
  reference_overlap(soup, grid).for_each_set([&](uint64_t, uint64_t) { ++exact; });
  EXPECT_EQ(exact, 2122u);
}

TEST(SharedCases, C20DuplicatedTriangleKeepsTheSolid) {
  const std::string bounds = " --bounds -0.0123,-0.0234,-0.0345,1.0123,1.0234,1.0345 --res 37 --solid parity";
  const glm::dvec3 lo(0.05), hi(0.95, 0.83, 0.71);
  std::string err;
  const nlohmann::json box =
      voxelize(write_scratch_file("c20.off", box_off(lo, hi)).string() + bounds, "c20");
  const nlohmann::json dup = voxelize(
      write_scratch_file("c20_dup.off", box_off(lo, hi, "3 4 5 6\n", 1)).string() + bounds, "c20_dup", &err);
  EXPECT_EQ(box["solid"]["inside_voxels"], 19251);
  EXPECT_EQ(dup["solid"]["inside_voxels"], 19251);
  EXPECT_EQ(dup["solid"]["mode"], "parity");
  EXPECT_NE(
      err.find(
          "1 triangles repeat an earlier triangle exactly (first: triangle 12); the copies were dropped"),
      std::string::npos)
      << err;
  EXPECT_EQ(err.find("not closed"), std::string::npos) << err;
}

}  // namespace
}  // namespace voxr
