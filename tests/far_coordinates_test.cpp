// Coordinates far from the origin (survey, CAD): world positions stay in double until they are relative to
// an anchor near the mesh (core/triangle_soup.h), so a mesh and the same mesh a million units away load to
// the same floats, voxelize to the same voxels and write the same header origin moved by the offset.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cstring>
#include <string>

#include "cli_support.h"
#include "core/mesh_loader.h"
#include "test_support.h"

namespace voxr {
namespace {

namespace fs = std::filesystem;

TEST(FarCoordinates, AnchorIsTheCornerRoundedToThePowerOfTwoOfTheSize) {
  EXPECT_EQ(choose_anchor(glm::dvec3(0.17, 0.28, 0.95), glm::dvec3(1.17, 1.28, 1.95)), glm::dvec3(0.0));
  EXPECT_EQ(
      choose_anchor(glm::dvec3(412345.17, 5823456.28, 122.95), glm::dvec3(412346.17, 5823457.28, 123.95)),
      glm::dvec3(412345.0, 5823456.0, 122.0));
  // Size 3 -> multiples of 4; a negative corner rounds down.
  EXPECT_EQ(choose_anchor(glm::dvec3(-1e6 - 1.0, 10.0, 0.0), glm::dvec3(-1e6 + 2.0, 11.0, 1.0)),
            glm::dvec3(-1e6 - 4.0, 8.0, 0.0));
  // A translation by a multiple of that power of two moves the anchor by exactly the translation.
  const glm::dvec3 lo(0.3, -0.7, 2.1), hi(1.2, 0.1, 2.5), shift(1e6, -3e6, 5e5);
  EXPECT_EQ(choose_anchor(lo + shift, hi + shift), choose_anchor(lo, hi) + shift);
}

// A random soup (floats in [0.5, 4): exact in double after adding 1e6) as OFF text, translated by `shift`.
std::string soup_off(const TriangleSoup& soup, const glm::dvec3& shift) {
  std::string s = fmt::format("OFF\n{} {} 0\n", soup.positions.size(), soup.triangles.size());
  for (const glm::vec4& p : soup.positions)
    s += fmt::format("{} {} {}\n", double(p.x) + shift.x, double(p.y) + shift.y, double(p.z) + shift.z);
  for (const glm::uvec4& t : soup.triangles) s += fmt::format("3 {} {} {}\n", t.x, t.y, t.z);
  return s;
}

TEST(FarCoordinates, TranslatedMeshLoadsToTheSameFloats) {
  const TriangleSoup soup = test::random_soup(11, 400, 0.5f, 4.0f, 0.8f);
  test::TempDir dir;
  const glm::dvec3 shift(1e6, -1e6, 1e6);
  const TriangleSoup near = load_mesh(dir.write("near.off", soup_off(soup, glm::dvec3(0.0))));
  const TriangleSoup far = load_mesh(dir.write("far.off", soup_off(soup, shift)));
  EXPECT_EQ(far.anchor - near.anchor, shift);
  ASSERT_EQ(near.positions.size(), far.positions.size());
  EXPECT_EQ(
      std::memcmp(near.positions.data(), far.positions.data(), near.positions.size() * sizeof(glm::vec4)), 0);
  EXPECT_EQ(near.triangles, far.triangles);
}

// "space origin: (x,y,z)" of a NRRD header.
glm::dvec3 nrrd_origin(const std::string& text) {
  glm::dvec3 o(0.0);
  const size_t at = text.find("space origin: (");
  if (at != std::string::npos)
    std::sscanf(text.c_str() + at, "space origin: (%lf,%lf,%lf)", &o.x, &o.y, &o.z);
  return o;
}

TEST(FarCoordinates, TranslatedMeshGivesIdenticalVoxels) {
  // A closed mesh, so the solid is compared too: the tetrahedra of a subdivided box are not needed, a box
  // with a dent (concave, non-convex caps) is enough.
  const std::string obj_near =
      "v 0.5 0.5 0.5\nv 3.5 0.5 0.5\nv 3.5 1.5 0.5\nv 1.5 1.5 0.5\nv 1.5 3.5 0.5\nv 0.5 3.5 0.5\n"
      "v 0.5 0.5 2.25\nv 3.5 0.5 2.25\nv 3.5 1.5 2.25\nv 1.5 1.5 2.25\nv 1.5 3.5 2.25\nv 0.5 3.5 2.25\n"
      "f 6 5 4 3 2 1\nf 7 8 9 10 11 12\nf 1 2 8 7\nf 2 3 9 8\nf 3 4 10 9\nf 4 5 11 10\nf 5 6 12 11\nf 6 1 7 "
      "12\n";
  std::string obj_far;
  for (size_t at = 0; at < obj_near.size();) {
    const size_t eol = obj_near.find('\n', at);
    const std::string line = obj_near.substr(at, eol - at);
    at = eol + 1;
    double x, y, z;
    obj_far += std::sscanf(line.c_str(), "v %lf %lf %lf", &x, &y, &z) == 3
                   ? fmt::format("v {} {} {}\n", x + 1e6, y - 1e6, z + 1e6)
                   : line + "\n";
  }
  std::string data[2], header[2];
  uint64_t inside[2] = {0, 0};
  const std::string names[2] = {"near", "far"};
  for (int m = 0; m < 2; ++m) {
    const fs::path mesh = test::write_scratch_file(names[m] + ".obj", m == 0 ? obj_near : obj_far);
    const fs::path out = test::scratch() / (names[m] + ".nrrd");
    const test::CliResult r =
        test::run_voxr("voxelize " + mesh.string() + " --res 48 --solid parity -q -o " + out.string());
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_EQ(r.err, "") << names[m];
    const std::string text = test::slurp(out);
    header[m] = text.substr(0, text.find("\n\n"));
    data[m] = text.substr(text.find("\n\n") + 2);
    const std::string in = test::slurp(test::scratch() / (names[m] + ".inside.nrrd"));
    for (char c : in.substr(in.find("\n\n") + 2)) inside[m] += c != 0;
  }
  EXPECT_TRUE(data[0] == data[1]) << "the surfaces differ";
  EXPECT_GT(inside[0], 1000u);
  EXPECT_EQ(inside[0], inside[1]);
  const glm::dvec3 o_near = nrrd_origin(header[0]), o_far = nrrd_origin(header[1]);
  EXPECT_NEAR(o_far.x - 1e6, o_near.x, 1e-9);
  EXPECT_NEAR(o_far.y + 1e6, o_near.y, 1e-9);
  EXPECT_NEAR(o_far.z - 1e6, o_near.z, 1e-9);
}

}  // namespace
}  // namespace voxr
