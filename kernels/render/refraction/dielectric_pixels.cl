/* dielectric_pixels.cl — the pixels a refraction method traces (host/render/dielectric_pixels.h): the list
 * of pixels whose primary sample is a dielectric surface, for the refraction kernels to run over, and the
 * ends of every other pixel's path (its primary sample: the path meets no dielectric).
 *
 * Inputs: the primary samples (one per pixel), the materials. Outputs: pixel_list[0 .. *pixel_count) the
 * listed pixels' indices (in no particular order: every writer indexes its outputs by pixel), *pixel_count
 * (zero before the launch), ends[id] = primary[id] for every pixel not listed. One work item per pixel; one
 * global atomic per work group. */
#include "refraction_path.h"

#ifndef LIST_GROUP
#define LIST_GROUP 64
#endif

__kernel __attribute__((reqd_work_group_size(LIST_GROUP, 1, 1))) void dielectric_pixels(
    __global const SurfaceSample* primary, uint count, __global const RenderMaterial* materials,
    uint material_count, __global uint* pixel_list, __global uint* pixel_count,
    __global SurfaceSample* ends) {
  __local uint group_count, group_base;
  const uint id = get_global_id(0);
  if (get_local_id(0) == 0) group_count = 0u;
  barrier(CLK_LOCAL_MEM_FENCE);
  uint slot = 0u;
  int listed = 0;
  if (id < count) {
    const SurfaceSample s = primary[id];
    listed = rp_sees_dielectric(s, materials, material_count);
    if (listed)
      slot = atomic_inc(&group_count);
    else
      ends[id] = s;
  }
  barrier(CLK_LOCAL_MEM_FENCE);
  if (get_local_id(0) == 0) group_base = group_count > 0u ? atomic_add(pixel_count, group_count) : 0u;
  barrier(CLK_LOCAL_MEM_FENCE);
  if (listed) pixel_list[group_base + slot] = id;
}
