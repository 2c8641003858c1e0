/* layout_probe.cl — writes the device compiler's size of every shared struct and offset of every shared
 * member (voxr_layout.h VOXR_LAYOUT_ENTRIES, in that order) and the lattice constant, so a test can compare
 * them with the host's (tests/layout_test.cpp).
 * out: values[0 .. entries]  shape: a single work item. */
#include "voxr_layout.h"

#define PROBE_SIZE(T) values[n++] = sizeof(T);
#define PROBE_OFFSET(T, field)                                                \
  {                                                                           \
    T probe;                                                                  \
    values[n++] = (uint)((__private char*)&probe.field - (__private char*)&probe); \
  }

__kernel void layout_probe(__global uint* values) {
  uint n = 0;
  VOXR_LAYOUT_ENTRIES(PROBE_SIZE, PROBE_OFFSET)
  values[n++] = VOXR_SUBVOXEL;
}
