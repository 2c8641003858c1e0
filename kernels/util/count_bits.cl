/* count_bits.cl — the number of set bits in an array of 32-bit words (voxels in a dense bit channel).
 * in:  words[0 .. n)
 * out: *total += the popcount of COUNT_WORDS consecutive words per work item (one 64-bit atomic each)
 * shape: one work item per COUNT_WORDS words. */
#pragma OPENCL EXTENSION cl_khr_int64_base_atomics : enable

#ifndef WG_SIZE
#define WG_SIZE 256
#endif
#ifndef COUNT_WORDS
#define COUNT_WORDS 64
#endif

__kernel __attribute__((reqd_work_group_size(WG_SIZE, 1, 1))) void count_bits(__global const uint* words,
                                                                               ulong n, __global ulong* total) {
  const ulong begin = (ulong)get_global_id(0) * COUNT_WORDS;
  if (begin >= n) return;
  const ulong end = min(begin + COUNT_WORDS, n);
  uint sum = 0;
  for (ulong w = begin; w < end; ++w) sum += popcount(words[w]);
  if (sum) atom_add(total, (ulong)sum);
}
