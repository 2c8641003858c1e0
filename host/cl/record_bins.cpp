#include "cl/record_bins.h"

#include <algorithm>

#include "cl/scan.h"
#include "voxr_layout.h"

namespace voxr {

namespace {

constexpr size_t kGroup = 256;

Defines expand_defines() {
  return {{"WG_SIZE", std::to_string(kGroup)}};
}

}  // namespace

std::vector<ProgramSpec> RecordBins::programs() {
  std::vector<ProgramSpec> specs = scan_programs();
  specs.push_back({"expand_copies.cl", expand_defines()});
  return specs;
}

void RecordBins::prepare(ClRuntime& cl, uint64_t triangles) {
  VOXR_CHECK_LE(triangles, uint64_t(0xffffffffu));  // the expand kernel counts them in 32 bits
  triangles_ = triangles;
  records_ = 0;
  batch_ = 0;
  expanded_ = false;
  counts_.ensure(cl, triangles * sizeof(cl_uint), "copy counts");
  boxes_.ensure(cl, triangles * sizeof(CopyBox), "copy boxes");
  offsets_.ensure(cl, triangles * sizeof(cl_ulong), "copy offsets");
}

void RecordBins::scan(ClRuntime& cl, uint64_t budget_bytes, const std::string& name, uint64_t* capacity) {
  cl::Buffer& total = total_.ensure(cl, sizeof(cl_ulong), "copy total");
  exclusive_scan(cl, ScanKind::kUintToUlong, counts_.buffer, offsets_.buffer, triangles_, total, name);
  const uint64_t most = std::min(std::max<uint64_t>(1, budget_bytes / sizeof(CopyRecord)), kMaxBatch);
  if (capacity && cl.counts_deferred() && *capacity > 0 && *capacity <= most) {
    records_ = batch_ = *capacity;
    cl.read_count_later(total, sizeof(cl_ulong), "readback " + name + " total",
                        [capacity, used = *capacity](uint64_t records) {
                          if (records <= used) return true;
                          *capacity = std::max(*capacity, ClRuntime::with_headroom(records));
                          return false;
                        });
    return;
  }
  cl_ulong records = 0;
  cl.download(total, &records, sizeof(records), "readback " + name + " total");
  records_ = records;
  batch_ = std::min(records_, most);
  if (capacity) *capacity = ClRuntime::with_headroom(records_);
}

uint64_t RecordBins::device_bytes() const {
  return triangles_ * (sizeof(cl_uint) + sizeof(CopyBox) + sizeof(cl_ulong)) + batch_ * sizeof(CopyRecord);
}

void RecordBins::for_each_batch(ClRuntime& cl, const std::string& name,
                                const std::function<void(const cl::Buffer&, uint32_t)>& consume) {
  if (records_ == 0) return;
  cl::Buffer& records = records_buffer_.ensure(cl, batch_ * sizeof(CopyRecord), "copy records");
  cl::Buffer& window_records = window_records_.ensure(cl, sizeof(cl_uint), "copy records in the batch");
  const bool single = batches() == 1;
  for (uint64_t begin = 0; begin < records_; begin += batch_) {
    const uint32_t count = uint32_t(std::min(batch_, records_ - begin));
    if (!(single && expanded_)) {
      cl::Kernel expand = cl.kernel("expand_copies.cl", "expand_copies", expand_defines());
      cl.launch(name, expand, count, kGroup, cl_uint(triangles_), offsets_.buffer, boxes_.buffer,
                total_.buffer, cl_ulong(begin), cl_uint(count), records, window_records);
      expanded_ = single;
    }
    consume(records, count);
  }
}

}  // namespace voxr
