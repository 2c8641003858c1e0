// The .vdb writer of the OpenVDB plugin (peers/vdb_write_abi.h): a brick of voxr's sparse grid is exactly one
// 8^3 LeafNode of OpenVDB's default tree (5-4-3), so each brick becomes a leaf built directly (bits
// transposed: voxr's voxel bit is x + 8 * (y + 8 * z), x fastest; a leaf's offset is (x << 6) | (y << 3) | z,
// z fastest), in parallel, and the leaves are added to the tree; no voxel goes through the tree's setValue.
#include <openvdb/io/Archive.h>
#include <openvdb/openvdb.h>
#include <tbb/parallel_for.h>

#include <bit>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <exception>
#include <fstream>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "peers/vdb_write_abi.h"

namespace {

using openvdb::Coord;

Coord brick_origin(const VoxrVdbWrite& w, uint64_t linear_brick) {
  const uint64_t bx = linear_brick % w.brick_dims[0];
  const uint64_t by = (linear_brick / w.brick_dims[0]) % w.brick_dims[1];
  const uint64_t bz = linear_brick / (uint64_t(w.brick_dims[0]) * w.brick_dims[1]);
  return Coord(int(bx * 8), int(by * 8), int(bz * 8));
}

// A grid holding value(rank) at every set voxel of the bricks (active), `background` elsewhere (inactive).
template <typename GridT, typename Value>
typename GridT::Ptr build_grid(const VoxrVdbWrite& w, const typename GridT::ValueType& background,
                               Value&& value) {
  using TreeT = typename GridT::TreeType;
  using LeafT = typename TreeT::LeafNodeType;
  static_assert(LeafT::DIM == 8, "a voxr brick is an 8^3 leaf");
  std::vector<std::unique_ptr<LeafT>> leaves(size_t(w.bricks));
  tbb::parallel_for(
      tbb::blocked_range<size_t>(0, size_t(w.bricks)), [&](const tbb::blocked_range<size_t>& r) {
        for (size_t b = r.begin(); b != r.end(); ++b) {
          auto leaf = std::make_unique<LeafT>(brick_origin(w, w.brick_index[b]), background, false);
          const uint32_t* words = w.brick_bits + b * 16;
          uint64_t rank = w.brick_rank[b];
          for (uint32_t word = 0; word < 16; ++word)
            for (uint32_t bits = words[word]; bits; bits &= bits - 1) {
              const uint32_t v = word * 32 + uint32_t(std::countr_zero(bits));
              const openvdb::Index offset = ((v & 7u) << 6) | (((v >> 3) & 7u) << 3) | (v >> 6);
              leaf->setValueOn(offset, value(rank++));
            }
          leaves[b] = std::move(leaf);
        }
      });
  auto tree = std::make_shared<TreeT>(background);
  for (auto& leaf : leaves) tree->addLeaf(leaf.release());  // the tree owns it from here
  return GridT::create(tree);
}

openvdb::math::Transform::Ptr make_transform(const VoxrVdbWrite& w) {
  const double* m = w.index_to_world;
  const openvdb::Vec3d origin(m[12], m[13], m[14]);
  if (w.axis_aligned) {
    auto xform = openvdb::math::Transform::createLinearTransform(w.voxel_size);
    xform->postTranslate(origin);
    return xform;
  }
  openvdb::math::Mat4d mat;
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) mat(r, c) = m[r * 4 + c];
  return openvdb::math::Transform::createLinearTransform(mat);
}

void describe(openvdb::GridBase& grid, const VoxrVdbWrite& w, const char* name,
              const openvdb::math::Transform::Ptr& xform) {
  grid.setName(name);
  grid.setTransform(xform);
  grid.setCreator(w.creator ? w.creator : "voxr");
  grid.setGridClass(openvdb::GRID_UNKNOWN);
  grid.insertMeta("voxr_dims",
                  openvdb::Vec3IMetadata(openvdb::Vec3i(int(w.dims[0]), int(w.dims[1]), int(w.dims[2]))));
  grid.setSaveFloatAsHalf(false);
}

// OpenVDB's archive writer on a stream voxr opens and checks: io::File::write does not report a failed write
// (a full disk left a truncated file and success). Seekable, as io::File writes: grid offsets in the file,
// so readers can load grids one at a time (delayed loading).
class CheckedArchive : public openvdb::io::Archive {
 public:
  void write_file(const char* path, const openvdb::GridPtrVec& grids, const openvdb::MetaMap& meta) const {
    std::vector<char> buffer(size_t(4) << 20);
    std::ofstream os;
    os.rdbuf()->pubsetbuf(buffer.data(), std::streamsize(buffer.size()));
    os.open(path, std::ios_base::out | std::ios_base::binary | std::ios_base::trunc);
    if (!os) throw std::runtime_error(std::string("cannot open the file: ") + std::strerror(errno));
    Archive::write(os, grids, /*seekable=*/true, meta);
    errno = 0;
    os.flush();
    const int flush_errno = errno;
    os.close();
    if (!os)
      throw std::runtime_error(std::string("write failed: ") +
                               (flush_errno ? std::strerror(flush_errno) : "stream error"));
  }
};

uint32_t compression_flags(uint32_t compression) {
  switch (compression) {
    case kVoxrVdbNone:
      return openvdb::io::COMPRESS_ACTIVE_MASK;
    case kVoxrVdbZip:
      return openvdb::io::COMPRESS_ZIP | openvdb::io::COMPRESS_ACTIVE_MASK;
    case kVoxrVdbDefault:
      return openvdb::io::Archive::hasBloscCompression() ? compression_flags(kVoxrVdbBlosc)
                                                         : compression_flags(kVoxrVdbZip);
    case kVoxrVdbBlosc:
      if (!openvdb::io::Archive::hasBloscCompression())
        throw std::runtime_error("this OpenVDB build has no Blosc compression");
      return openvdb::io::COMPRESS_BLOSC | openvdb::io::COMPRESS_ACTIVE_MASK;
  }
  throw std::runtime_error("unknown compression " + std::to_string(compression));
}

}  // namespace

extern "C" bool voxr_openvdb_write(const VoxrVdbWrite* w, char* error, size_t error_size) {
  try {
    if (w->abi_version != VOXR_VDB_ABI_VERSION)
      throw std::runtime_error("the OpenVDB plugin is of another voxr build (interface version " +
                               std::to_string(w->abi_version) + ", plugin " +
                               std::to_string(VOXR_VDB_ABI_VERSION) + ")");
    openvdb::initialize();
    const auto xform = make_transform(*w);
    openvdb::GridPtrVec grids;

    auto occupancy = build_grid<openvdb::BoolGrid>(*w, false, [](uint64_t) { return true; });
    describe(*occupancy, *w, "occupancy", xform);
    grids.push_back(occupancy);

    for (uint32_t c = 0; c < w->channel_count; ++c) {
      const VoxrVdbChannel& ch = w->channels[c];
      if (ch.type == kVoxrVdbInt32 && ch.components == 1) {
        const auto* v = static_cast<const int32_t*>(ch.values);
        auto grid = build_grid<openvdb::Int32Grid>(*w, 0, [v](uint64_t r) { return v[r]; });
        describe(*grid, *w, ch.name, xform);
        grids.push_back(grid);
      } else if (ch.type == kVoxrVdbFloat32 && ch.components == 1) {
        const auto* v = static_cast<const float*>(ch.values);
        auto grid = build_grid<openvdb::FloatGrid>(*w, 0.0f, [v](uint64_t r) { return v[r]; });
        describe(*grid, *w, ch.name, xform);
        grids.push_back(grid);
      } else if (ch.type == kVoxrVdbFloat32 && ch.components == 3) {
        const auto* v = static_cast<const float*>(ch.values);
        auto grid = build_grid<openvdb::Vec3SGrid>(*w, openvdb::Vec3s(0.0f), [v](uint64_t r) {
          return openvdb::Vec3s(v[3 * r], v[3 * r + 1], v[3 * r + 2]);
        });
        describe(*grid, *w, ch.name, xform);
        if (ch.vector_normal) {
          grid->setVectorType(openvdb::VEC_COVARIANT_NORMALIZE);
          grid->setIsInWorldSpace(false);
        }
        grids.push_back(grid);
      } else {
        throw std::runtime_error(std::string("channel ") + ch.name + ": unsupported value type");
      }
    }

    CheckedArchive archive;
    archive.setCompression(compression_flags(w->compression));
    openvdb::MetaMap meta;
    meta.insertMeta("creator", openvdb::StringMetadata(w->creator ? w->creator : "voxr"));
    archive.write_file(w->path, grids, meta);
    return true;
  } catch (const std::exception& e) {
    std::snprintf(error, error_size, "%s", e.what());
    return false;
  }
}
