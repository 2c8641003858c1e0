#include "stability/stability_voxels.h"

#include <algorithm>
#include <bit>

#include "bench/table1.h"
#include "io/image_file.h"
#include "util/error.h"
#include "voxelize/reference_slicemap.h"
#include "voxelize/reference_voxelizer.h"

namespace voxr {

const std::vector<std::string>& stability_methods() {
  return table1_methods();
}

bool is_conservative_method(const std::string& method) {
  const VoxelizeOptions options = table1_voxelize_options(method);
  return options.method != VoxelizeMethod::kSlicemap && options.mode == RasterMode::kConservative;
}

VoxelGrid MethodRunner::run(const std::string& method, const TriangleSoup& soup, const GridSpec& grid) {
  return voxelizer_.run(soup, grid, table1_voxelize_options(method));
}

VoxelGrid method_reference(const std::string& method, const TriangleSoup& soup, const GridSpec& grid) {
  const VoxelizeOptions options = table1_voxelize_options(method);
  if (options.method == VoxelizeMethod::kSlicemap)
    return reference_slicemap_voxels(reference_slicemap(soup, grid, options.slicing));
  return reference_voxelize(soup, grid, options.mode, ChannelSet{});
}

namespace {

void check_same_dims(const VoxelGrid& a, const VoxelGrid& b) {
  if (a.spec.dims != b.spec.dims || a.occ.size() != b.occ.size())
    fail("stability: comparing voxel grids of different dims ({}x{}x{} and {}x{}x{})", a.spec.dims.x,
         a.spec.dims.y, a.spec.dims.z, b.spec.dims.x, b.spec.dims.y, b.spec.dims.z);
}

}  // namespace

uint64_t missing_voxels(const VoxelGrid& result, const VoxelGrid& reference) {
  check_same_dims(result, reference);
  uint64_t n = 0;
  for (size_t w = 0; w < reference.occ.size(); ++w) n += std::popcount(reference.occ[w] & ~result.occ[w]);
  return n;
}

uint64_t differing_voxels(const VoxelGrid& a, const VoxelGrid& b) {
  check_same_dims(a, b);
  uint64_t n = 0;
  for (size_t w = 0; w < a.occ.size(); ++w) n += std::popcount(a.occ[w] ^ b.occ[w]);
  return n;
}

TriangleSoup transformed_soup(const TriangleSoup& soup, const glm::dmat4& transform) {
  std::vector<glm::dvec3> world(soup.positions.size());
  glm::dvec3 lo(std::numeric_limits<double>::max()), hi(-std::numeric_limits<double>::max());
  for (size_t v = 0; v < world.size(); ++v) {
    world[v] =
        glm::dvec3(transform * glm::dvec4(soup.anchor + glm::dvec3(glm::vec3(soup.positions[v])), 1.0));
    lo = glm::min(lo, world[v]);
    hi = glm::max(hi, world[v]);
  }
  TriangleSoup out;
  out.anchor = world.empty() ? glm::dvec3(0.0) : choose_anchor(lo, hi);
  for (const glm::dvec3& p : world) out.positions.push_back(glm::vec4(glm::vec3(p - out.anchor), 1.0f));
  for (const glm::uvec4& t : soup.triangles) out.triangles.push_back(t);
  return out;
}

std::string write_difference_picture(const VoxelGrid& result, const VoxelGrid& reference,
                                     const std::filesystem::path& dir, const std::string& name) {
  if (dir.empty()) return "";
  check_same_dims(result, reference);
  const glm::uvec3 d = result.spec.dims;
  const uint32_t scale = std::max(1u, 160u / std::max(d.x, d.y));
  ImageRgba image(d.x * scale, d.y * scale, glm::vec4(1.0f));
  for (uint32_t j = 0; j < d.y; ++j)
    for (uint32_t i = 0; i < d.x; ++i) {
      bool common = false, extra = false, missing = false;
      for (uint32_t k = 0; k < d.z; ++k) {
        const bool r = result.occupied(i, j, k), e = reference.occupied(i, j, k);
        common |= r && e;
        extra |= r && !e;
        missing |= e && !r;
      }
      const glm::vec4 colour = missing  ? glm::vec4(0.1f, 0.25f, 1.0f, 1.0f)
                               : extra  ? glm::vec4(1.0f, 0.1f, 0.1f, 1.0f)
                               : common ? glm::vec4(0.45f, 0.45f, 0.45f, 1.0f)
                                        : glm::vec4(1.0f);
      // Row j = 0 at the bottom of the picture.
      for (uint32_t y = 0; y < scale; ++y)
        for (uint32_t x = 0; x < scale; ++x) image.at(i * scale + x, (d.y - 1 - j) * scale + y) = colour;
    }
  std::filesystem::create_directories(dir);
  const std::string file = name + ".png";
  write_image(image, dir / file);
  return file;
}

}  // namespace voxr
