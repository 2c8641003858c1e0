#include "bench/voxelize_cases.h"

namespace voxr {

VoxelizeOptions VoxelizeCase::options() const {
  VoxelizeOptions o;
  o.method = parse_voxelize_method(method);
  o.mode = parse_raster_mode(mode);
  o.channels = ChannelSet::parse(channels);
  if (!solid.empty()) o.solid = parse_solid_mode(solid);
  o.validate();
  return o;
}

std::vector<std::string> VoxelizeCase::cli_flags() const {
  std::vector<std::string> flags = {"--method",   method,   "--mode",   mode,
                                    "--channels", channels, "--layout", layout};
  if (!solid.empty()) {
    flags.push_back("--solid");
    flags.push_back(solid);
  }
  return flags;
}

const std::vector<VoxelizeCase>& voxelize_cases() {
  static const std::vector<VoxelizeCase> cases = {
      {"occ", "hybrid", "conservative", "occ", ""},
      {"count-normal", "hybrid", "conservative", "occ,count,normal", ""},
      {"all-channels", "hybrid", "conservative", "occ,count,normal,material", ""},
      {"count-normal-color", "hybrid", "conservative", "occ,count,normal,color", ""},
      {"center", "hybrid", "center", "occ", ""},
      {"slice", "slice", "conservative", "occ", ""},
      {"solid-parity", "hybrid", "conservative", "occ", "parity"},
      {"solid-flood", "hybrid", "conservative", "occ", "flood"},
      {"sparse-occ", "hybrid", "conservative", "occ", "", "sparse"},
      {"sparse-count-normal", "hybrid", "conservative", "occ,count,normal", "", "sparse"},
  };
  return cases;
}

const VoxelizeCase& find_voxelize_case(const std::string& name) {
  std::string known;
  for (const VoxelizeCase& c : voxelize_cases()) {
    if (c.name == name) return c;
    known += fmt::format("{}{}", known.empty() ? "" : ", ", c.name);
  }
  fail("unknown benchmark case '{}' (cases: {})", name, known);
}

}  // namespace voxr
