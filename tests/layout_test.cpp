// One layout, two readers: the device compiler must agree with the host on every struct of
// kernels/common/voxr_layout.h (sizes and member offsets, the list VOXR_LAYOUT_ENTRIES).
#include <gtest/gtest.h>

#include <cstddef>
#include <string>
#include <vector>

#include "test_support.h"
#include "voxelize/snapped_triangle.h"
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
  return entries;
}

// The lattice the host's snapping actually uses (snapped_triangle.cpp, which the CPU references and the
// splitter share): the snapped coordinate of a vertex one voxel from the origin. Measured, not the macro, so
// the comparison with the device's VOXR_SUBVOXEL below is between two values obtained independently.
cl_uint host_snap_lattice() {
  TriangleSoup soup;
  soup.positions = {glm::vec4(1, 0, 0, 1), glm::vec4(0, 1, 0, 1), glm::vec4(0, 0, 1, 1)};
  soup.triangles = {glm::uvec4(0, 1, 2, 0)};
  const SnappedTriangle t = snap_triangle(test::unit_grid({4, 4, 4}).world_to_grid(), soup, 0);
  EXPECT_EQ(t.v[1][0], 0);
  return cl_uint(t.v[0][0]);
}

TEST(Layout, DeviceAgreesWithHostOnEverySharedRecord) {
  const std::vector<Entry> host = host_entries();
  ASSERT_GT(host.size(), 30u);
  ClRuntime& cl = test::runtime();
  // The probe writes every entry, then its VOXR_SUBVOXEL.
  const size_t values = host.size() + 1;
  cl::Buffer out = cl.buffer(values * sizeof(cl_uint), "layout probe");
  cl::Kernel probe = cl.kernel("layout_probe.cl", "layout_probe");
  cl.launch("layout_probe", probe, 1, 1, out);
  std::vector<cl_uint> device(values);
  cl.download(out, device.data(), device.size() * sizeof(cl_uint), "readback layout");
  cl.finish();
  for (size_t i = 0; i < host.size(); ++i) EXPECT_EQ(device[i], host[i].value) << host[i].what;
  EXPECT_EQ(device.back(), host_snap_lattice()) << "device VOXR_SUBVOXEL vs the lattice the host snaps to";
}

}  // namespace
}  // namespace voxr
