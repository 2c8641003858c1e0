/* shadow_transmittance.cl — the transparent shadow map's prefix pass (Chang & Lai, TR 1688 §4.1; PG 2011
 * §4): walk each column of the light's grid from the light outwards, summing every voxel's optical depth,
 * and store the transmittance at the far face of each slab (shadow_frame.h's packing) up to the column's last
 * change, and the value from there on (`tails`: slabs stored, value).
 *
 * Per-voxel optical depth (method SHADOW_VOXEL), from the write count and the writers' material (the largest
 * material id among them, grid channel `material`):
 *   sheet       count x -ln(transmittance): each write is one crossing of the column's centre ray in centre
 *               mode (conservative mode writes more voxels per crossing and over-counts);
 *   opaque      blocks: everything beyond is 0;
 *   dielectric  each write toggles inside/outside; sigma_a x the column's length inside (half a slab where
 *               it toggles).
 * SHADOW_UNIFORM (Eisemann & Decoret 2006 §5): every occupied voxel adds one constant optical depth;
 * SHADOW_UNIFORM_OPAQUE (their opaque case, for casters that are all opaque): every occupied voxel blocks. */
#include "grid_view.h"
#include "shadow_frame.h"

#define SHADOW_VOXEL 0
#define SHADOW_UNIFORM 1
#define SHADOW_UNIFORM_OPAQUE 2

#ifndef SHADOW_GROUP
#define SHADOW_GROUP 64
#endif

__kernel __attribute__((reqd_work_group_size(SHADOW_GROUP, 1, 1))) void shadow_transmittance(
    VOXR_GRID_VIEW_PARAMS, ShadowFrame frame, __global const RenderMaterial* materials, uint material_count,
    uint method, uint conservative, float uniform_r, float uniform_g, float uniform_b, __global uint* volume,
    __global uint2* tails) {
  const GridView g = VOXR_GRID_VIEW();
  const uint column = get_global_id(0);
  const uint dx = frame.dims[0], dy = frame.dims[1], dz = frame.dims[2];
  if (column >= dx * dy) return;
  const uint i = column % dx, j = column / dx;
  __global uint* out = volume + (ulong)column * dz;
  float3 tau = (float3)(0.0f);
  float3 sigma = (float3)(0.0f); /* absorption of the dielectric the column is inside, 0 outside */
  int inside = 0;
  uint packed = sf_pack((float3)(1.0f)); /* exp(-tau), packed: recomputed only where tau changes */
  uint written = 0;                      /* slabs stored so far; the rest of the column is `packed` */
  const ulong slab_voxels = (ulong)dx * dy;
  ulong v = gv_linear(&g, (int)i, (int)j, 0);
  uint k = 0;
  int in_run = 0; /* conservative: inside a run of dielectric voxels along the column */
  float3 run_absorption = (float3)(0.0f);
  for (; k < dz; ++k, v += slab_voxels) {
    const int occupied = gv_occupied(&g, v);
    uint count = 0;
    int kind = -1;
    RenderMaterial mat;
    if (occupied && method == SHADOW_VOXEL) {
      const uint r = gv_rank(&g, v);
      count = gv_count(&g, r);
      mat = materials[min(gv_material(&g, r), material_count - 1u)];
      kind = (int)mat.kind;
    }
    int changed = 0;
    if (in_run && kind != VOXR_MATERIAL_DIELECTRIC) {
      /* Conservative mode writes one crossing into several voxels of a column, and a voxel near an edge
       * between two triangles of one surface twice: counts cannot tell crossings apart. A run of dielectric
       * voxels is taken as one boundary (a closed dielectric thinner than about two voxels merges its two
       * faces into one run, and its shadow is then wrong). */
      inside = !inside;
      sigma = inside ? run_absorption : (float3)(0.0f);
      in_run = 0;
      changed = 1;
    }
    if (inside) {
      tau += sigma * sf_slab_length(&frame, i, j, k);
      changed = 1;
    }
    if (occupied) {
      changed = 1;
      if (method == SHADOW_UNIFORM) {
        tau += (float3)(uniform_r, uniform_g, uniform_b);
      } else if (method == SHADOW_UNIFORM_OPAQUE || kind == VOXR_MATERIAL_OPAQUE) {
        /* Blocks everything from its slab on: the column's tail is 0 from slab k. */
        for (; written < k; ++written) out[written] = packed;
        packed = 0u;
        break;
      } else if (kind == VOXR_MATERIAL_SHEET) {
        const float3 t =
            max((float3)(mat.transmittance[0], mat.transmittance[1], mat.transmittance[2]), (float3)(1e-30f));
        tau += (float)count * -log(t);
      } else if (conservative) {
        in_run = 1;
        run_absorption = (float3)(mat.absorption[0], mat.absorption[1], mat.absorption[2]);
      } else if (count & 1u) {
        /* One boundary inside the slab: half of the slab is inside (the entered or the left one). */
        const float3 a = (float3)(mat.absorption[0], mat.absorption[1], mat.absorption[2]);
        const float half_slab = 0.5f * sf_slab_length(&frame, i, j, k);
        if (inside) {
          tau -= sigma * half_slab; /* added for the whole slab above */
          sigma = (float3)(0.0f);
        } else {
          tau += a * half_slab;
          sigma = a;
        }
        inside = !inside;
      }
    }
    if (changed) {
      /* Slabs since the last change keep the previous value; this one gets the new. */
      for (; written < k; ++written) out[written] = packed;
      packed = sf_pack(exp(-tau));
      out[k] = packed;
      written = k + 1;
    }
  }
  /* Most columns end in empty space (below the casters): their tail is stored once, not slab by slab. */
  tails[column] = (uint2)(written, packed);
}
