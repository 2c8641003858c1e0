#include "voxelize/device_mesh.h"

#include <optional>

namespace voxr {


DeviceMesh::DeviceMesh(ClRuntime& cl, const TriangleSoup& soup, const Bounds* bounds) {
  if (soup.triangle_count() > 0xffffffffull) fail("{} triangles are more than 2^32-1", soup.triangle_count());
  triangle_count_ = uint32_t(soup.triangle_count());
  bounds_ = bounds ? *bounds : soup.bounds();
  const uint64_t pos_bytes = soup.positions.size() * sizeof(glm::vec4);
  const uint64_t tri_bytes = soup.triangles.size() * sizeof(glm::uvec4);
  positions_ = cl.buffer(pos_bytes, "vertex positions", CL_MEM_READ_ONLY);
  triangles_ = cl.buffer(tri_bytes, "triangle indices", CL_MEM_READ_ONLY);
  cl.finish();
  const auto before = cl.profiler().stats();
  cl.upload(positions_, soup.positions.data(), pos_bytes, "upload positions");
  cl.upload(triangles_, soup.triangles.data(), tri_bytes, "upload triangles");
  cl.finish("uploading the mesh");
  upload_ms_ = cl.profiler().since(before).upload_ms;
}

DeviceMesh upload_mesh(ClRuntime& cl, const TriangleSoup& soup, const GridSpec& grid, SplitCull cull,
                       const Bounds* bounds) {
  uint64_t split = 0;
  const std::optional<TriangleSoup> pieces = split_oversized_triangles(soup, grid, &split, cull);
  DeviceMesh mesh(cl, pieces ? *pieces : soup, bounds);
  mesh.triangles_split_ = split;
  return mesh;
}

}  // namespace voxr
