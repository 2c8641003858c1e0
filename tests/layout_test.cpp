// One layout, two readers: the device compiler must agree with the host on every struct of
// kernels/voxr_layout.h (sizes and member offsets, the list VOXR_LAYOUT_ENTRIES).
#include <gtest/gtest.h>

#include <cstddef>
#include <string>
#include <vector>

#include "test_support.h"
#include "voxr_layout.h"

namespace voxr {
namespace {

struct Entry {
  std::string what;
  cl_uint value;
};

std::vector<Entry> host_entries() {
  std::vector<Entry> entries;
#define HOST_SIZE(T) entries.push_back({"sizeof(" #T ")", cl_uint(sizeof(T))});
#define HOST_OFFSET(T, field) \
  entries.push_back({"offsetof(" #T ", " #field ")", cl_uint(offsetof(T, field))});
  VOXR_LAYOUT_ENTRIES(HOST_SIZE, HOST_OFFSET)
#undef HOST_SIZE
#undef HOST_OFFSET
  entries.push_back({"VOXR_SUBVOXEL", VOXR_SUBVOXEL});
  return entries;
}

TEST(Layout, DeviceAgreesWithHostOnEverySharedRecord) {
  const std::vector<Entry> host = host_entries();
  ASSERT_GT(host.size(), 30u);
  ClRuntime& cl = test::runtime();
  cl::Buffer out = cl.buffer(host.size() * sizeof(cl_uint), "layout probe");
  cl::Kernel probe = cl.kernel("layout_probe.cl", "layout_probe");
  cl.launch("layout_probe", probe, 1, 1, out);
  std::vector<cl_uint> device(host.size());
  cl.download(out, device.data(), device.size() * sizeof(cl_uint), "readback layout");
  cl.finish();
  for (size_t i = 0; i < host.size(); ++i) EXPECT_EQ(device[i], host[i].value) << host[i].what;
}

}  // namespace
}  // namespace voxr
