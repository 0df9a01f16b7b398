// The local half of post-sorting (thesis §3.2.8 "Sorting", §3.3.3; ldm_impls/common/post_sort.h):
// a shader-local array of LDM_SORT_LOCAL depths, sorted with insertion sort, which beats
// the asymptotically better sorts on the short lists of a pixel [Knowles et al. 2012].
// Depths are held and moved as their float bits, so that what is written back is bit for
// bit what was stored; strict comparisons keep equal depths in their order (stable).
// Work counted (in the includer's "sort" sub-pass): the insertion sort's depth comparisons
// and the entries it writes into the local array (shifts and placements), added once per
// list; both depend on the order the list arrived in.
#ifndef LDM_POST_SORT_GLSL
#define LDM_POST_SORT_GLSL

#include "common/work_counters.glsl"

uint sort_local[LDM_SORT_LOCAL];  // float bits

// Sorts sort_local[0 .. count) by ascending depth; count <= LDM_SORT_LOCAL.
void insertion_sort_local(uint count) {
#if WORK_COUNTING
  uint sort_comparisons = 0u, sort_moves = 0u;
#endif
  for (uint i = 1u; i < count; ++i) {
    const uint bits = sort_local[i];
    const float depth = uintBitsToFloat(bits);
    uint j = i;
    // Not `for (; j > 0u && sort_local[j - 1u] > depth; --j)`: Mesa's llvmpipe (22.3)
    // miscompiles that short-circuit on a private array and loses values.
    while (j > 0u) {
      const uint previous = sort_local[j - 1u];
#if WORK_COUNTING
      ++sort_comparisons;
#endif
      if (!(uintBitsToFloat(previous) > depth)) break;
      sort_local[j] = previous;
#if WORK_COUNTING
      ++sort_moves;
#endif
      --j;
    }
    sort_local[j] = bits;
#if WORK_COUNTING
    ++sort_moves;
#endif
  }
  work_add(comparisons, sort_comparisons);
  work_add(moves, sort_moves);
}

#endif
