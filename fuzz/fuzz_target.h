// Shared body of the libFuzzer targets for the mesh readers (scripts/fuzz.sh builds and runs them). Each
// target reads the input with one reader and triangulates the result as load_mesh does. voxr::Error is the
// expected outcome for bad input; anything else (another exception, a crash, a sanitizer report, a hang,
// memory beyond -rss_limit_mb) is a finding. The readers' promises are checked too: a one-line message that
// starts with the file name, faces whose corners add up to the index list, indices in range, coordinates
// finite and within text::kMaxCoordinate.
#pragma once

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <string_view>

#include "mesh/polygon_mesh.h"
#include "mesh/polygon_triangulation.h"
#include "util/error.h"
#include "util/host_array.h"
#include "util/text_scan.h"

namespace voxr::fuzz {

[[noreturn]] inline void broken(const char* what) {
  std::fprintf(stderr, "fuzz: broken promise: %s\n", what);
  std::abort();
}

inline void check_mesh(const PolygonMesh& mesh) {
  size_t corners = 0;
  for (uint32_t n : mesh.face_sizes) corners += n;
  if (corners != mesh.indices.size()) broken("face sizes do not add up to the index count");
  if (!mesh.materials.empty() && mesh.materials.size() != mesh.face_sizes.size())
    broken("materials not one per face");
  for (uint32_t i : mesh.indices)
    if (i >= mesh.positions.size()) broken("index out of range");
  for (const glm::dvec3& p : mesh.positions)
    for (int c = 0; c < 3; ++c)
      if (!(std::abs(p[c]) <= text::kMaxCoordinate)) broken("coordinate not finite or too large");
}

inline void check_triangles(const PolygonMesh& mesh, const HostArray<glm::uvec4>& triangles) {
  for (const glm::uvec4& t : triangles)
    if (t.x >= mesh.positions.size() || t.y >= mesh.positions.size() || t.z >= mesh.positions.size())
      broken("triangle index out of range");
}

// Runs `read` (returns a PolygonMesh), checks and triangulates what it returns; a voxr::Error must be one
// line starting with `name`.
template <typename Read>
int run(const std::string& name, Read&& read) {
  try {
    const PolygonMesh mesh = read();
    check_mesh(mesh);
    HostArray<glm::uvec4> triangles;
    TriangulationReport report;
    triangulate(mesh, triangles, report);
    check_triangles(mesh, triangles);
    for (const std::string& w : report.warnings(name))
      if (w.rfind(name, 0) != 0 || w.find('\n') != std::string::npos) broken("warning not one line");
  } catch (const Error& e) {
    const std::string_view message = e.what();
    if (message.rfind(name, 0) != 0) broken("error message does not start with the file name");
    if (message.find('\n') != std::string_view::npos) broken("error message spans lines");
  }
  return 0;
}

}  // namespace voxr::fuzz
