#include "voxelize/raster_mode.h"

#include "util/error.h"

namespace voxr {

RasterMode parse_raster_mode(std::string_view name) {
  if (name == "conservative") return RasterMode::kConservative;
  if (name == "center" || name == "centre") return RasterMode::kCenter;
  fail("unknown mode '{}' (modes: conservative, center)", name);
}

const char* raster_mode_name(RasterMode mode) {
  return mode == RasterMode::kConservative ? "conservative" : "center";
}

}  // namespace voxr
