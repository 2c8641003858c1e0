// TriangleSoup::bounds and validate_soup against their plain definitions: the same bits, the same first
// error.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <string>

#include "core/triangle_soup.h"
#include "util/error.h"

namespace voxr {
namespace {

// The definition: Bounds::extend with every corner, in triangle order.
Bounds reference_bounds(const TriangleSoup& soup) {
  Bounds b;
  for (const glm::uvec4& t : soup.triangles)
    for (int c = 0; c < 3; ++c) b.extend(glm::vec3(soup.positions[t[c]]));
  return b;
}

// The definition: the first triangle, corner by corner, with a bad index or a vertex that is not finite.
std::string reference_error(const TriangleSoup& soup, const std::string& source) {
  for (size_t i = 0; i < soup.triangles.size(); ++i)
    for (int c = 0; c < 3; ++c) {
      const uint32_t v = soup.triangles[i][c];
      if (v >= soup.positions.size())
        return fmt::format("{}: triangle {} uses vertex {} but there are only {} vertices", source, i, v,
                           soup.positions.size());
      const glm::vec3 p(soup.positions[v]);
      if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
        return fmt::format("{}: vertex {} of triangle {} is not finite ({}, {}, {})", source, v, i, p.x, p.y,
                           p.z);
    }
  return "";
}

size_t reference_degenerate(const TriangleSoup& soup) {
  size_t n = 0;
  for (const glm::uvec4& t : soup.triangles) {
    const glm::vec3 a(soup.positions[t.x]), b(soup.positions[t.y]), c(soup.positions[t.z]);
    n += glm::cross(b - a, c - a) == glm::vec3(0.0f);
  }
  return n;
}

std::string validate_error(const TriangleSoup& soup, const std::string& source) {
  try {
    validate_soup(soup, source);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

bool same_bits(const Bounds& a, const Bounds& b) {
  return std::memcmp(&a.lo, &b.lo, sizeof a.lo) == 0 && std::memcmp(&a.hi, &b.hi, sizeof a.hi) == 0;
}

// Coordinates drawn from a few values, so that ties, +0 and -0, repeated and collinear corners are common.
TriangleSoup tie_soup(uint32_t seed, size_t vertices, size_t triangles) {
  std::mt19937 rng(seed);
  const float values[] = {0.0f, -0.0f, 1.0f, -1.0f, 0.5f, 2.0f, -2.0f, 1e-30f, -1e-30f};
  std::uniform_int_distribution<size_t> value(0, std::size(values) - 1);
  std::uniform_int_distribution<uint32_t> vertex(0, uint32_t(vertices - 1));
  TriangleSoup soup;
  for (size_t i = 0; i < vertices; ++i)
    soup.positions.push_back(glm::vec4(values[value(rng)], values[value(rng)], values[value(rng)], 1.0f));
  for (size_t i = 0; i < triangles; ++i) soup.triangles.push_back({vertex(rng), vertex(rng), vertex(rng), 0});
  return soup;
}

TEST(TriangleSoup, BoundsHaveTheBitsOfTheCornerByCornerFold) {
  for (uint32_t seed = 1; seed <= 300; ++seed) {
    TriangleSoup soup = tie_soup(seed, 2 + seed % 40, 1 + seed % 70);
    if (seed % 3 == 0) {
      // A vertex no triangle uses may hold anything; one that is used may be NaN (bounds skip NaN).
      soup.positions.push_back(glm::vec4(std::numeric_limits<float>::infinity(), -1e30f, 1e30f, 1.0f));
      soup.positions[0].y = std::nanf("");
    }
    SCOPED_TRACE(seed);
    const Bounds expected = reference_bounds(soup), actual = soup.bounds();
    EXPECT_TRUE(same_bits(expected, actual))
        << "expected " << expected.lo.x << " " << expected.lo.y << " " << expected.lo.z << " / "
        << expected.hi.x << " " << expected.hi.y << " " << expected.hi.z << ", got " << actual.lo.x << " "
        << actual.lo.y << " " << actual.lo.z << " / " << actual.hi.x << " " << actual.hi.y << " "
        << actual.hi.z;
  }
  // Which zero is kept depends on the order: -0 first, then +0 (and the reverse) in triangle order.
  TriangleSoup soup;
  soup.positions = {{0.0f, 1, 1, 1}, {-0.0f, 1, 1, 1}, {1, 1, 1, 1}};
  soup.triangles = {{1, 2, 2, 0}, {0, 2, 2, 0}};
  EXPECT_TRUE(std::signbit(soup.bounds().lo.x));
  soup.triangles = {{0, 2, 2, 0}, {1, 2, 2, 0}};
  EXPECT_FALSE(std::signbit(soup.bounds().lo.x));
  EXPECT_TRUE(TriangleSoup().bounds().empty());
}

TEST(TriangleSoup, ValidateCountsDegenerateTrianglesAsDefined) {
  for (uint32_t seed = 1; seed <= 200; ++seed) {
    const TriangleSoup soup = tie_soup(seed, 2 + seed % 30, 1 + seed % 90);
    SCOPED_TRACE(seed);
    EXPECT_EQ(validate_soup(soup, "s"), reference_degenerate(soup));
  }
}

TEST(TriangleSoup, ValidateNamesTheFirstTriangleAtFault) {
  const float nan = std::nanf(""), inf = std::numeric_limits<float>::infinity();
  for (uint32_t seed = 1; seed <= 300; ++seed) {
    std::mt19937 rng(seed);
    TriangleSoup soup = tie_soup(seed, 10, 20);
    // Spoil a few vertices (used or not) and indices.
    std::uniform_int_distribution<uint32_t> vertex(0, 9), triangle(0, 19), corner(0, 2), kind(0, 3);
    for (uint32_t k = 0; k < seed % 4; ++k) {
      switch (kind(rng)) {
        case 0:
          soup.positions[vertex(rng)].x = nan;
          break;
        case 1:
          soup.positions[vertex(rng)].z = -inf;
          break;
        case 2:
          soup.triangles[triangle(rng)][corner(rng)] = 10 + vertex(rng);
          break;
        default:
          soup.positions.push_back(glm::vec4(nan, inf, 0.0f, 1.0f));
          break;  // unused
      }
    }
    SCOPED_TRACE(seed);
    EXPECT_EQ(validate_error(soup, "mesh.obj"), reference_error(soup, "mesh.obj"));
  }
  TriangleSoup soup = tie_soup(7, 10, 20);
  soup.triangles[5].y = 99;                     // bad index in triangle 5
  soup.positions[soup.triangles[9].x].x = nan;  // used first by triangle 9 or earlier
  soup.positions.push_back(glm::vec4(nan));     // never used
  EXPECT_EQ(validate_error(soup, "m"), reference_error(soup, "m"));
  EXPECT_NE(validate_error(soup, "m"), "");
  EXPECT_EQ(validate_error(TriangleSoup(), "m"), "m: the mesh has no triangles");
}

}  // namespace
}  // namespace voxr
