#include "io/volume_writer.h"

#include <cctype>
#include <string>

#include <fmt/format.h>

#include "io/atomic_file.h"
#include "io/binvox_writer.h"
#include "io/npz_writer.h"
#include "io/nrrd_writer.h"
#include "io/vdb_writer.h"
#include "io/vox_writer.h"
#include "io/vti_writer.h"
#include "util/error.h"

namespace voxr {

namespace fs = std::filesystem;

namespace {

enum class Format { kNrrd, kVti, kBinvox, kVox, kVdb, kNpz };

Format volume_format(const fs::path& out) {
  std::string ext = out.extension().string();
  for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
  if (ext == ".nrrd") return Format::kNrrd;
  if (ext == ".vti") return Format::kVti;
  if (ext == ".binvox") return Format::kBinvox;
  if (ext == ".vox") return Format::kVox;
  if (ext == ".vdb") return Format::kVdb;
  if (ext == ".npz") return Format::kNpz;
  if (ext.empty())
    fail("{}: no extension to choose the volume format by (.nrrd, .vti, .binvox, .vox, .vdb, .npz)",
         out.string());
  fail("{}: unknown volume format '{}' (formats: .nrrd, .vti, .binvox, .vox, .vdb, .npz)", out.string(),
       out.extension().string());
}

}  // namespace

std::vector<fs::path> write_volume(const VoxelGrid& grid, const fs::path& out) {
  switch (volume_format(out)) {
    case Format::kNrrd:
      return write_nrrd(grid, out);
    case Format::kVti:
      return {write_vti(grid, out)};
    // The single-set formats get the solid (surface and interior) when there is one.
    case Format::kBinvox:
      return {write_binvox(grid.inside.empty() ? grid : solid_occupancy(grid), out)};
    case Format::kVox:
      return {write_vox(grid.inside.empty() ? grid : solid_occupancy(grid), out)};
    case Format::kVdb:
      return {write_vdb(grid, out)};
    case Format::kNpz:
      return {write_npz(grid, out)};
  }
  throw InternalError("unhandled volume format");
}

std::vector<fs::path> write_volume(const SparseVoxelGrid& grid, const fs::path& out) {
  switch (volume_format(out)) {
    case Format::kNrrd:
      return write_nrrd(grid, out);
    case Format::kVti:
      return {write_vti(grid, out)};
    // Small formats (binvox is read whole by its readers, .vox holds at most 256^3): through a dense copy.
    case Format::kBinvox:
      check_output_path(out);
      check_binvox_dims(out, grid.spec.dims);
      return {write_binvox(to_dense(grid), out)};
    case Format::kVox:
      check_output_path(out);
      check_vox_dims(out, grid.spec.dims);
      return {write_vox(to_dense(grid), out)};
    case Format::kVdb:
      return {write_vdb(grid, out)};
    case Format::kNpz:
      return {write_npz(grid, out)};
  }
  throw InternalError("unhandled volume format");
}

void fit_request_to_format(GridRequest& request, const fs::path& out) {
  if (out.empty()) return;
  if (volume_format(out) == Format::kBinvox && !request.dims) request.dims = glm::uvec3(request.resolution);
}

void check_volume_output(const fs::path& out, const glm::uvec3& dims) {
  check_output_path(out);
  const Format format = volume_format(out);
  if (format == Format::kBinvox) check_binvox_dims(out, dims);
  if (format == Format::kVox) check_vox_dims(out, dims);
  if (format == Format::kVdb) check_vdb_writer(out);
}

}  // namespace voxr
