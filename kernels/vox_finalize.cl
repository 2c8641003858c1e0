/* vox_finalize.cl — unit normals of set voxels from their fixed-point normal sums (zero where the sum
 * cancels, e.g. a voxel touched by both sides of a thin sheet).
 * in: nsum[3*r+q]  out: normal[3*r+q]  shape: one work item per set voxel. */
#ifndef WG_SIZE
#define WG_SIZE 64
#endif

__kernel __attribute__((reqd_work_group_size(WG_SIZE, 1, 1))) void vox_finalize(
    __global const int* nsum, __global float* normal, uint voxel_count) {
  const uint r = get_global_id(0);
  if (r >= voxel_count) return;
  const ulong base = 3 * (ulong)r;
  const float3 s = (float3)((float)nsum[base], (float)nsum[base + 1], (float)nsum[base + 2]);
  const float len = length(s);
  const float3 n = len > 0.0f ? s / len : (float3)(0.0f);
  normal[base] = n.x;
  normal[base + 1] = n.y;
  normal[base + 2] = n.z;
}
