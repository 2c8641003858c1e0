#include "cl/scan.h"

namespace voxr {

namespace {

constexpr size_t kScanGroup = 256;
constexpr size_t kScanItems = 8;
constexpr uint64_t kTile = kScanGroup * kScanItems;

Defines scan_defines(ScanKind kind) {
  Defines d = {{"WG_SIZE", std::to_string(kScanGroup)}, {"SCAN_ITEMS", std::to_string(kScanItems)}};
  switch (kind) {
    case ScanKind::kUintToUlong:
      d.push_back({"SCAN_IN", "uint"});
      d.push_back({"SCAN_OUT", "ulong"});
      break;
    case ScanKind::kRankedWords:
      d.push_back({"SCAN_IN", "uint"});
      d.push_back({"SCAN_OUT", "ulong"});
      d.push_back({"SCAN_RANKED_WORDS", "1"});
      break;
    case ScanKind::kUlongToUlong:
      d.push_back({"SCAN_IN", "ulong"});
      d.push_back({"SCAN_OUT", "ulong"});
      break;
  }
  return d;
}

}  // namespace

std::vector<ProgramSpec> scan_programs() {
  std::vector<ProgramSpec> specs;
  for (ScanKind kind : {ScanKind::kUintToUlong, ScanKind::kRankedWords, ScanKind::kUlongToUlong})
    specs.push_back({"scan.cl", scan_defines(kind)});
  return specs;
}

uint64_t exclusive_scan(ClRuntime& cl, ScanKind kind, const cl::Buffer& in, cl::Buffer& out, uint64_t n,
                        const std::string& name) {
  if (n == 0) return 0;
  const Defines defines = scan_defines(kind);
  const uint64_t tiles = (n + kTile - 1) / kTile;
  cl::Buffer tile_sums = cl.buffer(tiles * sizeof(cl_ulong), name + " tile totals");
  cl::Kernel scan_tiles = cl.kernel("scan.cl", "scan_tiles", defines);
  cl.launch(name, scan_tiles, tiles * kScanGroup, kScanGroup, in, out, tile_sums, cl_ulong(n));
  if (tiles == 1) {
    cl_ulong total = 0;
    cl.download(tile_sums, &total, sizeof(total), "readback " + name + " total");
    return total;
  }
  cl::Buffer tile_offsets = cl.buffer(tiles * sizeof(cl_ulong), name + " tile offsets");
  const uint64_t total = exclusive_scan(cl, ScanKind::kUlongToUlong, tile_sums, tile_offsets, tiles, name);
  cl::Kernel scan_add = cl.kernel("scan.cl", "scan_add", defines);
  cl.launch(name, scan_add, tiles * kScanGroup, kScanGroup, out, tile_offsets, cl_ulong(n));
  return total;
}

}  // namespace voxr
