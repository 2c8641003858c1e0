// Copy records (cl/record_bins.h, kernels/util/expand_copies.cl): every copy of every triangle, in order,
// against a plain CPU expansion, in one batch and in batches that split triangles, with triangles of no
// copies between others and enough triangles for a scan of several tiles.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <utility>
#include <vector>

#include "cl/record_bins.h"
#include "test_support.h"
#include "voxr_layout.h"

namespace voxr {
namespace {

using Record = std::pair<uint32_t, uint32_t>;  // triangle, cell

std::vector<Record> cpu_expand(const std::vector<uint32_t>& counts, const std::vector<CopyBox>& boxes) {
  std::vector<Record> out;
  for (uint32_t t = 0; t < counts.size(); ++t)
    for (uint32_t q = 0; q < counts[t]; ++q)
      out.push_back({t, VOXR_CELL(VOXR_CELL_COLUMN(boxes[t].first) + q % boxes[t].width,
                                  VOXR_CELL_ROW(boxes[t].first) + q / boxes[t].width)});
  return out;
}

// Bins `counts` and `boxes` with batches of `batch` records and returns every record for_each_batch hands
// over, `passes` times in a row.
std::vector<Record> device_expand(const std::vector<uint32_t>& counts, const std::vector<CopyBox>& boxes,
                                  uint64_t batch, int passes, RecordBins& bins) {
  ClRuntime& cl = test::runtime();
  bins.prepare(cl, counts.size());
  cl::Buffer c = bins.counts(), b = bins.boxes();
  cl.upload(c, counts.data(), counts.size() * 4, "upload test counts");
  cl.upload(b, boxes.data(), boxes.size() * sizeof(CopyBox), "upload test boxes");
  bins.scan(cl, batch * sizeof(CopyRecord), "test scan");
  std::vector<Record> out;
  for (int pass = 0; pass < passes; ++pass)
    bins.for_each_batch(cl, "test expand", [&](const cl::Buffer& records, uint32_t count) {
      std::vector<CopyRecord> got(count);
      cl.download(records, got.data(), count * sizeof(CopyRecord), "readback test records");
      for (const CopyRecord& r : got) out.push_back({r.triangle, r.cell});
    });
  return out;
}

TEST(RecordBins, ExpandsEveryCopyInOrderInBatches) {
  const std::vector<uint32_t> counts = {3, 0, 0, 7, 1, 0, 12, 0};
  const std::vector<CopyBox> boxes = {
      {VOXR_CELL(2u, 5u), 3}, {0, 0}, {0, 0}, {VOXR_CELL(0u, 9u), 7}, {VOXR_CELL(4u, 4u), 1}, {0, 0},
      {VOXR_CELL(1u, 0u), 4}, {0, 0}};
  const std::vector<Record> expected = cpu_expand(counts, boxes);
  ASSERT_EQ(expected.size(), 23u);
  for (const uint64_t batch : {uint64_t(1000), uint64_t(5), uint64_t(1)}) {
    RecordBins bins;
    const std::vector<Record> got = device_expand(counts, boxes, batch, 2, bins);
    EXPECT_EQ(bins.records(), 23u);
    EXPECT_EQ(bins.batch_records(), std::min<uint64_t>(batch, 23));
    const uint64_t per_batch = std::min<uint64_t>(batch, 23);
    EXPECT_EQ(bins.batches(), (23 + per_batch - 1) / per_batch);
    std::vector<Record> twice = expected;
    twice.insert(twice.end(), expected.begin(), expected.end());
    EXPECT_EQ(got, twice) << "batch " << batch;
  }
}

TEST(RecordBins, ManyTrianglesAcrossScanTiles) {
  std::mt19937 rng(18);
  std::vector<uint32_t> counts(5000);
  std::vector<CopyBox> boxes(counts.size());
  for (size_t t = 0; t < counts.size(); ++t) {
    const uint32_t width = 1 + uint32_t(rng() % 9), rows = rng() % 4 == 0 ? 0 : 1 + uint32_t(rng() % 6);
    counts[t] = width * rows;
    const uint32_t column = uint32_t(rng() % 1000), row = uint32_t(rng() % 1000);
    boxes[t] = {VOXR_CELL(column, row), width};
  }
  const std::vector<Record> expected = cpu_expand(counts, boxes);
  for (const uint64_t batch : {uint64_t(1) << 20, uint64_t(4099)}) {
    RecordBins bins;
    EXPECT_EQ(device_expand(counts, boxes, batch, 1, bins), expected) << "batch " << batch;
    EXPECT_EQ(bins.records(), expected.size());
  }
}

TEST(RecordBins, NoTrianglesNoRecords) {
  RecordBins bins;
  EXPECT_TRUE(device_expand({}, {}, 100, 1, bins).empty());
  EXPECT_EQ(bins.batches(), 0u);
}

}  // namespace
}  // namespace voxr
