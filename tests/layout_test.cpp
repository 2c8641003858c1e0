// One layout, two readers: the device compiler must agree with the host on kernels/voxr_layout.h.
#include <gtest/gtest.h>

#include <cstddef>

#include "test_support.h"
#include "voxr_layout.h"

namespace voxr {
namespace {

TEST(Layout, DeviceAgreesWithHost) {
  ClRuntime& cl = test::runtime();
  cl::Buffer out = cl.buffer(8 * sizeof(cl_uint), "layout probe");
  cl::Kernel probe = cl.kernel("layout_probe.cl", "layout_probe");
  cl.launch("layout_probe", probe, 1, 1, out);
  cl_uint device[8] = {};
  cl.download(out, device, sizeof(device), "readback layout");
  cl.finish();
  const cl_uint host[8] = {sizeof(VoxGridParams),
                           offsetof(VoxGridParams, world_to_grid),
                           offsetof(VoxGridParams, dims),
                           offsetof(VoxGridParams, rows_per_copy),
                           offsetof(VoxGridParams, triangle_count),
                           sizeof(VoxCopy),
                           offsetof(VoxCopy, slice_block),
                           VOXR_SUBVOXEL};
  for (int i = 0; i < 8; ++i) EXPECT_EQ(device[i], host[i]) << "entry " << i;
}

}  // namespace
}  // namespace voxr
