/* vox_lists.cl — the per-voxel triangle lists of the slice family (VoxelizeOptions::triangle_lists): count
 * -> scan -> fill -> sort. The count is the count channel (pass 1: the triangles the exact rule puts in each
 * set voxel); list_counts prepares it for the exclusive scan (scan.cl) whose result is the lists' offsets;
 * pass 2 of the raster kernels (vox_scanline.h) appends ids in any order through a cursor per voxel; then
 * list_sort orders every list ascending, so the result is deterministic.
 * shape: one work item per rank (entries + 1 for list_counts, entries for list_sort). */
#ifndef WG_SIZE
#define WG_SIZE 64
#endif

/* counts[r] = count[r] for the set voxels r < min(entries, *set_total), 0 for the rest of the entries and
 * for counts[entries] (so the scan's entry past the last voxel is the total of pairs). */
__kernel __attribute__((reqd_work_group_size(WG_SIZE, 1, 1))) void list_counts(
    __global const uint* count, __global const ulong* set_total, uint entries, __global uint* counts) {
  const uint r = get_global_id(0);
  if (r > entries) return;
  counts[r] = r < entries && (ulong)r < *set_total ? count[r] : 0u;
}

/* Insertion sort of each list [offsets[r], offsets[r + 1]) (lists hold a few triangles); lists that reach
 * past `capacity` were not filled (the frame is rendered again with more room). */
__kernel __attribute__((reqd_work_group_size(WG_SIZE, 1, 1))) void list_sort(
    __global const ulong* offsets, __global uint* ids, uint entries, __global const ulong* set_total,
    ulong capacity) {
  const uint r = get_global_id(0);
  if (r >= entries || (ulong)r >= *set_total) return;
  const ulong first = offsets[r], end = offsets[r + 1];
  if (end > capacity) return;
  for (ulong a = first + 1; a < end; ++a) {
    const uint id = ids[a];
    ulong b = a;
    while (b > first && ids[b - 1] > id) {
      ids[b] = ids[b - 1];
      --b;
    }
    ids[b] = id;
  }
}
