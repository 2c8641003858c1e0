// Copy records, the duplication step that the slice voxelizer (a triangle's slabs x blocks of rows), the
// slicemap voxelizer (its tiles of column centres) and the kernel rasterizer (its 8x8-pixel tiles) share:
// their setup kernel writes per triangle a copy count and a CopyBox (voxr_layout.h); scan() makes the
// exclusive prefix sum of the counts and splits the records into batches within a byte budget;
// for_each_batch() expands each batch (kernels/util/expand_copies.cl: one work item per record, a binary
// search over the scan) and hands it to the consumer kernel. The buffers are kept and grown, so one
// RecordBins per pipeline (or per raster target) reuses them run after run.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "cl/cl_runtime.h"
#include "cl/scratch_buffers.h"

namespace voxr {

class RecordBins {
 public:
  // Most records in one batch, whatever the budget: consumers count them in 32 bits.
  static constexpr uint64_t kMaxBatch = uint64_t(1) << 30;

  // The programs scan() and for_each_batch() use (the scan and the expand kernel), to build ahead of timed
  // work.
  static std::vector<ProgramSpec> programs();

  // Sizes the buffers the setup kernel writes for `triangles` (< 2^32) triangles and forgets the last
  // binning.
  void prepare(ClRuntime& cl, uint64_t triangles);
  const cl::Buffer& counts() const { return counts_.buffer; }  // uint per triangle: its copies
  const cl::Buffer& boxes() const { return boxes_.buffer; }    // CopyBox per triangle: where they lie

  // Scans the counts the setup kernel wrote, under the profiler name `name`, and waits for the record total
  // (one readback). Batches then hold at most `budget_bytes` of records (at least 1, at most kMaxBatch).
  // With a `capacity` (the caller's, one per use of the binning: the last total with headroom, 0 when
  // unknown) and cl.counts_deferred(), once the capacity is known and fits one batch, it does not wait:
  // records() is the capacity, the one batch runs over it (the expand kernel stops at the true total on
  // the device) and the total is checked against it with the caller's next wait (ClRuntime::read_count_later;
  // an exceeded capacity grows). A scan that waits sets *capacity from the total.
  void scan(ClRuntime& cl, uint64_t budget_bytes, const std::string& name, uint64_t* capacity = nullptr);

  uint64_t triangles() const { return triangles_; }
  uint64_t records() const { return records_; }      // all batches together (deferred: the capacity)
  uint64_t batch_records() const { return batch_; }  // records per batch (the last may hold fewer)
  uint64_t batches() const { return batch_ == 0 ? 0 : (records_ + batch_ - 1) / batch_; }
  // Device bytes this binning uses: per triangle its count, box and offset; one batch of records.
  uint64_t device_bytes() const;

  // Calls `consume(records, count)` once per batch, in order, with the batch's CopyRecords (record
  // window_begin + i at i) after expanding them under the profiler name `name`. A binning of one batch is
  // expanded once: later calls reuse its records. `count` is exact unless the scan was deferred; the true
  // count of the batch is on the device in window_records().
  void for_each_batch(ClRuntime& cl, const std::string& name,
                      const std::function<void(const cl::Buffer&, uint32_t)>& consume);
  // The records of the batch consume() was last handed (uint), for a kernel whose launch may run past them.
  const cl::Buffer& window_records() const { return window_records_.buffer; }

 private:
  uint64_t triangles_ = 0, records_ = 0, batch_ = 0;
  bool expanded_ = false;  // the single batch's records are in place
  GrowingBuffer counts_, boxes_, offsets_, records_buffer_, total_, window_records_;
};

}  // namespace voxr
