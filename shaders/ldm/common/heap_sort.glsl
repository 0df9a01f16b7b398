// The in-place half of post-sorting for the array structures (DF-buffer, PPFLA): heap sort
// of one pixel's range in storage memory, O(n log n) steps and no extra memory.
// Why not insertion sort: its O(n^2) steps (~262,000 at 1,024 entries) run past Mesa
// llvmpipe's loop limiter, which silently ends every loop of an invocation after 65,535
// iterations in all (LP_MAX_TGSI_LOOP_ITERATIONS, shared by all loops of a shader), so
// long ranges came out partly sorted. Heap sort takes ~12,000 iterations at 1,024 entries
// (~55,000 at 4,096). It is not stable; only equal floats with different bits (-0.0, +0.0)
// can tell, and the query API allows ties in any order.
// The includer defines, over indices 0 .. count of the range:
//   uint heap_load(uint i);  void heap_store(uint i, uint bits);  (depths as float bits)
// and counts the bytes they move. Work counted here (in the includer's "sort" sub-pass,
// added once per heap_sort_in_place): `comparisons`, the depth comparisons, and `moves`,
// the heap_store calls; both depend on the order the range arrived in.
#ifndef LDM_HEAP_SORT_GLSL
#define LDM_HEAP_SORT_GLSL

#include "common/work_counters.glsl"

// Counted only where the includer's structure declares both names (WORK_<name> is the
// counter's slot): DF-buffer and PPFLA do.
#if WORK_COUNTING && defined(WORK_comparisons) && defined(WORK_moves)
uint heap_work_comparisons = 0u, heap_work_moves = 0u;
#define HEAP_COUNT(statement) statement
#define HEAP_WORK_ADD(name, n) work_add(name, n)
#else
#define HEAP_COUNT(statement)
#define HEAP_WORK_ADD(name, n)
#endif

// Moves the entry at `root` down the max-heap [0, end) to where it belongs.
void heap_sift_down(uint root, uint end) {
  const uint bits = heap_load(root);
  const float depth = uintBitsToFloat(bits);
  uint at = root;
  while (2u * at + 1u < end) {
    uint child = 2u * at + 1u;
    uint child_bits = heap_load(child);
    if (child + 1u < end) {
      const uint right_bits = heap_load(child + 1u);
      HEAP_COUNT(++heap_work_comparisons);
      if (uintBitsToFloat(right_bits) > uintBitsToFloat(child_bits)) {
        child += 1u;
        child_bits = right_bits;
      }
    }
    HEAP_COUNT(++heap_work_comparisons);
    if (!(uintBitsToFloat(child_bits) > depth)) break;
    heap_store(at, child_bits);
    HEAP_COUNT(++heap_work_moves);
    at = child;
  }
  heap_store(at, bits);
  HEAP_COUNT(++heap_work_moves);
}

// Sorts entries [0, count) by ascending depth.
void heap_sort_in_place(uint count) {
  if (count < 2u) return;
  HEAP_COUNT(heap_work_comparisons = 0u; heap_work_moves = 0u);
  for (uint i = count / 2u; i > 0u; --i) heap_sift_down(i - 1u, count);
  for (uint end = count - 1u; end > 0u; --end) {
    const uint deepest = heap_load(0u);
    heap_store(0u, heap_load(end));
    heap_store(end, deepest);
    HEAP_COUNT(heap_work_moves += 2u);
    heap_sift_down(0u, end);
  }
  HEAP_WORK_ADD(comparisons, heap_work_comparisons);
  HEAP_WORK_ADD(moves, heap_work_moves);
}

#endif
