// The local half of post-sorting (thesis §3.2.8 "Sorting", §3.3.3; ldm_impls/common/post_sort.h):
// a shader-local array of LDM_SORT_LOCAL depths, sorted with insertion sort, which beats
// the asymptotically better sorts on the short lists of a pixel [Knowles et al. 2012].
// Depths are held and moved as their float bits, so that what is written back is bit for
// bit what was stored; strict comparisons keep equal depths in their order (stable).
#ifndef LDM_POST_SORT_GLSL
#define LDM_POST_SORT_GLSL

uint sort_local[LDM_SORT_LOCAL];  // float bits

// Sorts sort_local[0 .. count) by ascending depth; count <= LDM_SORT_LOCAL.
void insertion_sort_local(uint count) {
  for (uint i = 1u; i < count; ++i) {
    const uint bits = sort_local[i];
    const float depth = uintBitsToFloat(bits);
    uint j = i;
    // Not `for (; j > 0u && sort_local[j - 1u] > depth; --j)`: Mesa's llvmpipe (22.3)
    // miscompiles that short-circuit on a private array and loses values.
    while (j > 0u) {
      const uint previous = sort_local[j - 1u];
      if (!(uintBitsToFloat(previous) > depth)) break;
      sort_local[j] = previous;
      --j;
    }
    sort_local[j] = bits;
  }
}

#endif
