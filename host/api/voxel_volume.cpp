// voxr::VoxelVolume (include/voxr/voxr.h) over the job's dense VoxelGrid or SparseVoxelGrid.
#include <cstring>

#include "api/volume_impl.h"
#include "io/volume_writer.h"
#include "util/error.h"

namespace voxr {

namespace {

template <typename T>
std::span<const T> view(const std::vector<T>& v) {
  return {v.data(), v.size()};
}

void check_size(size_t got, uint64_t want, const char* what) {
  if (got != want) fail("VoxelVolume::{}: the output holds {} values, the volume needs {}", what, got, want);
}

}  // namespace

VoxelVolume::VoxelVolume(std::shared_ptr<const Impl> impl) : impl_(std::move(impl)) {}

std::array<uint32_t, 3> VoxelVolume::dims() const {
  const glm::uvec3 d = impl_->grid.dims;
  return {d.x, d.y, d.z};
}

double VoxelVolume::voxel_size() const {
  return impl_->grid.voxel_size;
}

std::array<double, 16> VoxelVolume::index_to_world() const {
  // world = anchor + origin + axes * (voxel_size * ijk), as GridSpec places voxel corners.
  const GridSpec& g = impl_->grid;
  std::array<double, 16> m{};
  for (int c = 0; c < 3; ++c)
    for (int r = 0; r < 3; ++r) m[c * 4 + r] = double(g.axes[c][r]) * double(g.voxel_size);
  for (int r = 0; r < 3; ++r) m[12 + r] = g.anchor[r] + double(g.origin[r]);
  m[15] = 1.0;
  return m;
}

std::string VoxelVolume::channels() const {
  return impl_->result.channels().to_string();
}
bool VoxelVolume::sparse() const {
  return impl_->result.sparse;
}
uint64_t VoxelVolume::voxels_set() const {
  return impl_->result.stats.voxels_set;
}
uint64_t VoxelVolume::inside_voxels() const {
  return impl_->result.stats.inside_voxels;
}
const VoxelizeReport& VoxelVolume::report() const {
  return impl_->report;
}

void VoxelVolume::occupancy(std::span<uint8_t> out) const {
  const VoxelizeResult& r = impl_->result;
  const uint64_t n = impl_->grid.voxel_count();
  check_size(out.size(), n, "occupancy");
  if (!r.sparse) {
    expand_bits(r.dense.occ, 0, n, out.data());
    return;
  }
  std::memset(out.data(), 0, out.size());
  r.bricks.for_each_set(
      [&](uint32_t i, uint32_t j, uint32_t k, uint64_t) { out[impl_->grid.linear_index(i, j, k)] = 1; });
}

void VoxelVolume::inside(std::span<uint8_t> out) const {
  const VoxelizeResult& r = impl_->result;
  const uint64_t n = impl_->grid.voxel_count();
  check_size(out.size(), n, "inside");
  if (r.sparse || r.dense.inside.empty())
    std::memset(out.data(), 0, out.size());
  else
    expand_bits(r.dense.inside, 0, n, out.data());
}

void VoxelVolume::occupied_indices(std::span<uint32_t> out) const {
  const VoxelizeResult& r = impl_->result;
  check_size(out.size(), 3 * r.stats.voxels_set, "occupied_indices");
  if (r.sparse) {
    r.bricks.for_each_set([&](uint32_t i, uint32_t j, uint32_t k, uint64_t rank) {
      out[3 * rank] = i;
      out[3 * rank + 1] = j;
      out[3 * rank + 2] = k;
    });
    return;
  }
  const glm::uvec3 d = impl_->grid.dims;
  r.dense.for_each_set([&](uint64_t linear, uint64_t rank) {
    out[3 * rank] = uint32_t(linear % d.x);
    out[3 * rank + 1] = uint32_t((linear / d.x) % d.y);
    out[3 * rank + 2] = uint32_t(linear / (uint64_t(d.x) * d.y));
  });
}

std::span<const uint32_t> VoxelVolume::count() const {
  const VoxelizeResult& r = impl_->result;
  return view(r.sparse ? r.bricks.count : r.dense.count);
}

std::span<const float> VoxelVolume::normal() const {
  const VoxelizeResult& r = impl_->result;
  const std::vector<glm::vec3>& n = r.sparse ? r.bricks.normal : r.dense.normal;
  static_assert(sizeof(glm::vec3) == 3 * sizeof(float));
  return {n.empty() ? nullptr : &n[0].x, 3 * n.size()};
}

std::span<const uint32_t> VoxelVolume::material() const {
  const VoxelizeResult& r = impl_->result;
  return view(r.sparse ? r.bricks.material : r.dense.material);
}

std::span<const uint8_t> VoxelVolume::color() const {
  // RGBA8 with R in the low byte: on a little-endian host the bytes are R, G, B, A.
  static_assert(std::endian::native == std::endian::little);
  const VoxelizeResult& r = impl_->result;
  const std::vector<uint32_t>& c = r.sparse ? r.bricks.color : r.dense.color;
  return {reinterpret_cast<const uint8_t*>(c.data()), 4 * c.size()};
}

std::vector<std::string> VoxelVolume::save(const std::string& path) const {
  const VoxelizeResult& r = impl_->result;
  check_volume_output(path, impl_->grid.dims);
  const std::vector<std::filesystem::path> written =
      r.sparse ? write_volume(r.bricks, path) : write_volume(r.dense, path);
  return {written.begin(), written.end()};
}

}  // namespace voxr
