// Named meshes for benchmarks, built the same way on every machine: procedural generators, the
// Debian-packaged meshes (scripts/fetch-meshes.sh, looked up in $VOXR_MESH_DIR, default data/meshes) and
// midpoint subdivision for the million-triangle sizes. A name is BASE or BASExN with N = 4^levels:
// "torus" (800), "bunny" (69 K), "bunnyx16" (1.1 M), "armadillo" (52 K), "armadillox16" (832 K),
// "dragon" (20 K), "elephant" (89 K), "shark" (10 K, with holes), "sharkx64" (652 K).
#pragma once

#include <string>
#include <vector>

#include "core/triangle_soup.h"

namespace voxr {

struct BenchMesh {
  std::string name;
  TriangleSoup soup;
};

// Throws voxr::Error for an unknown name, a factor that is not a power of 4, or a missing mesh file
// (naming scripts/fetch-meshes.sh).
BenchMesh make_bench_mesh(const std::string& name);

// Gives every vertex of `soup` an opaque colour from its position in the soup's bounds (R, G, B = x, y, z
// from 0 to 255), the colour benchmarks' input.
void color_by_position(TriangleSoup& soup);

// The sweep of `voxr bench voxelize` by default.
const std::vector<std::string>& default_bench_meshes();

}  // namespace voxr
