#include "voxelize/device_mesh.h"

#include <optional>

namespace voxr {

DeviceMesh::DeviceMesh(ClRuntime& cl, const TriangleSoup& soup, const Bounds* bounds) {
  if (soup.triangle_count() > 0xffffffffull) fail("{} triangles are more than 2^32-1", soup.triangle_count());
  triangle_count_ = uint32_t(soup.triangle_count());
  bounds_ = bounds ? *bounds : soup.bounds();
  anchor_ = soup.anchor;
  const uint64_t pos_bytes = soup.positions.size() * sizeof(glm::vec4);
  const uint64_t tri_bytes = soup.triangles.size() * sizeof(glm::uvec4);
  cl.finish();
  const auto before = cl.profiler().stats();
  in_place_ =
      cl.host_buffer(positions_, soup.positions.data(), pos_bytes, "vertex positions", "upload positions");
  in_place_ &=
      cl.host_buffer(triangles_, soup.triangles.data(), tri_bytes, "triangle indices", "upload triangles");
  cl.finish("uploading the mesh");
  upload_ms_ = cl.profiler().since(before).upload_ms;
}

DeviceMesh::DeviceMesh(cl::Buffer positions, cl::Buffer triangles, uint32_t count, const Bounds& bounds,
                       uint64_t triangles_split)
    : positions_(std::move(positions)),
      triangles_(std::move(triangles)),
      triangle_count_(count),
      bounds_(bounds),
      triangles_split_(triangles_split) {}

std::unique_ptr<DeviceMesh> upload_split_mesh(ClRuntime& cl, const TriangleSoup& soup, const GridSpec& grid,
                                              SplitCull cull, const Bounds* bounds) {
  uint64_t split = 0;
  std::optional<TriangleSoup> pieces = split_oversized_triangles(soup, grid, &split, cull);
  if (!pieces) return nullptr;
  // The pieces live as long as the mesh whose buffers may use them in place.
  const Bounds input = bounds ? *bounds : soup.bounds();
  auto owned = std::make_shared<const TriangleSoup>(std::move(*pieces));
  auto mesh = std::make_unique<DeviceMesh>(cl, *owned, &input);
  mesh->anchor_ = soup.anchor;
  mesh->pieces_ = std::move(owned);
  mesh->triangles_split_ = split;
  return mesh;
}

DeviceMesh upload_mesh(ClRuntime& cl, const TriangleSoup& soup, const GridSpec& grid, SplitCull cull,
                       const Bounds* bounds) {
  std::unique_ptr<DeviceMesh> split = upload_split_mesh(cl, soup, grid, cull, bounds);
  return split ? std::move(*split) : DeviceMesh(cl, soup, bounds);
}

}  // namespace voxr
