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

void exclusive_scan(ClRuntime& cl, ScanKind kind, const cl::Buffer& in, cl::Buffer& out, uint64_t n,
                    cl::Buffer& total, const std::string& name) {
  if (n == 0) {
    cl.fill_zero(total, sizeof(cl_ulong), "clear");
    return;
  }
  const Defines defines = scan_defines(kind);
  const uint64_t tiles = (n + kTile - 1) / kTile;
  cl::Kernel scan_tiles = cl.kernel("scan.cl", "scan_tiles", defines);
  if (tiles == 1) {  // the one tile's total is the grand total
    cl.launch(name, scan_tiles, kScanGroup, kScanGroup, in, out, total, cl_ulong(n));
    return;
  }
  cl::Buffer tile_sums = cl.buffer(tiles * sizeof(cl_ulong), name + " tile totals");
  cl.launch(name, scan_tiles, tiles * kScanGroup, kScanGroup, in, out, tile_sums, cl_ulong(n));
  cl::Buffer tile_offsets = cl.buffer(tiles * sizeof(cl_ulong), name + " tile offsets");
  exclusive_scan(cl, ScanKind::kUlongToUlong, tile_sums, tile_offsets, tiles, total, name);
  cl::Kernel scan_add = cl.kernel("scan.cl", "scan_add", defines);
  cl.launch(name, scan_add, tiles * kScanGroup, kScanGroup, out, tile_offsets, cl_ulong(n));
}

uint64_t exclusive_scan(ClRuntime& cl, ScanKind kind, const cl::Buffer& in, cl::Buffer& out, uint64_t n,
                        const std::string& name) {
  if (n == 0) return 0;
  cl::Buffer total = cl.buffer(sizeof(cl_ulong), name + " total");
  exclusive_scan(cl, kind, in, out, n, total, name);
  cl_ulong value = 0;
  cl.download(total, &value, sizeof(value), "readback " + name + " total");
  return value;
}

}  // namespace voxr
