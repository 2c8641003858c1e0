#include "io/volume_writer.h"

#include <cctype>
#include <string>

#include <fmt/format.h>

#include "io/atomic_file.h"
#include "io/binvox_writer.h"
#include "io/nrrd_writer.h"
#include "io/vox_writer.h"
#include "io/vti_writer.h"
#include "util/error.h"

namespace voxr {

namespace fs = std::filesystem;

namespace {

enum class Format { kNrrd, kVti, kBinvox, kVox };

Format volume_format(const fs::path& out) {
  std::string ext = out.extension().string();
  for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
  if (ext == ".nrrd") return Format::kNrrd;
  if (ext == ".vti") return Format::kVti;
  if (ext == ".binvox") return Format::kBinvox;
  if (ext == ".vox") return Format::kVox;
  if (ext.empty())
    fail("{}: no extension to choose the volume format by (.nrrd, .vti, .binvox, .vox)", out.string());
  fail("{}: unknown volume format '{}' (formats: .nrrd, .vti, .binvox, .vox)", out.string(),
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
}

std::vector<std::filesystem::path> write_volume(const SparseVoxelGrid& grid,
                                                const std::filesystem::path& out) {
  return write_volume(to_dense(grid), out);
}

}  // namespace voxr
