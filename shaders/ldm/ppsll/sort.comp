// PPSLL sorting pass (thesis §3.2.8 "Sorting", §3.3.3): one invocation per LDM pixel of all
// views. The list's depths are copied into the local array, insertion-sorted, and written
// back along the same nodes in ascending order: the links stay, the values move, so the
// sorted lists are read by the unchanged list query. A list longer than LDM_SORT_LOCAL is
// merge-sorted in place by relinking its nodes (counted).
//
// Work counted (Ppsll::work_counters(), "sort"): invocations, each list's length, the sorts'
// comparisons and moves (post_sort.glsl; the merge sort's relinks), and the bytes at every
// access site, tallied per invocation: heads read and rewritten; nodes read through
// next_node() / depth_bits() (bytes_loaded_nodes, which depends only on the lists' lengths,
// so that one more pass over a list shows as a deterministic count) and written; the depths
// the merge sort compares (bytes_loaded_nodes_compared: how many depends on the order).
layout(local_size_x = 64) in;

#include "common/work_counters.glsl"
#include "ldm/common/compute_grid.glsl"
#include "ldm/common/list_nodes.glsl"
#include "ldm/common/post_sort.glsl"

layout(std430, binding = LDM_STRUCTURE_BINDING0) restrict buffer PpsllData {
  uint data[];
};
layout(binding = LDM_COUNTER_BINDING, offset = 4) uniform atomic_uint lists_sorted_in_place;

#if WORK_COUNTING
uint work_node_loads = 0u, work_node_stores = 0u, work_compared_loads = 0u;
uint work_comparisons = 0u, work_relinks = 0u;
uint work_merge_length = 0u;  // nodes the merge sort's first round took: the list's length
#define PPSLL_COUNT(statement) statement
#else
#define PPSLL_COUNT(statement)
#endif

uint next_node(uint node) {
  PPSLL_COUNT(++work_node_loads);
  return data[list_next_slot(node)];
}
uint depth_bits(uint node) {
  PPSLL_COUNT(++work_node_loads);
  return data[list_depth_slot(node)];
}
float node_depth(uint node) { return uintBitsToFloat(depth_bits(node)); }
// A depth the merge sort compares: how many it reads depends on the order of the list.
float compared_depth(uint node) {
  PPSLL_COUNT(++work_compared_loads);
  return uintBitsToFloat(data[list_depth_slot(node)]);
}

void set_next(uint node, uint next) {
  PPSLL_COUNT(++work_node_stores);
  data[list_next_slot(node)] = next;
}

// Bottom-up merge sort of the list by relinking its nodes: runs of 1, 2, 4, ... nodes are
// merged pairwise until one run is left; O(n log n) steps and no extra memory. Stable: on
// equal depths the earlier run's node goes first, as in the local insertion sort. Why not
// insertion sort through the nodes: its O(n^2) steps (~262,000 at 1,024 nodes) ran past
// Mesa llvmpipe's loop limiter, which silently ends every loop of an invocation after
// 65,535 iterations in all (LP_MAX_TGSI_LOOP_ITERATIONS), leaving lists partly sorted; this
// takes ~15,000 at 1,024 nodes (~50,000 at 3,000). Returns the new head.
uint merge_sort_list(uint head) {
  for (uint width = 1u;; width *= 2u) {
    uint rest = head;  // the nodes not merged yet in this round
    uint merged_head = 0u, merged_tail = 0u;
    uint merges = 0u;
    while (rest != 0u) {
      ++merges;
      uint a = rest, a_left = 0u;
      uint b = rest;
      while (b != 0u && a_left < width) {
        b = next_node(b);
        ++a_left;
      }
      uint b_left = width;
      // Every node's next is read when it is taken, before its link is rewritten.
      while (a_left > 0u || (b_left > 0u && b != 0u)) {
        uint taken;
        const bool take_b = a_left == 0u ||
                            (b_left > 0u && b != 0u && compared_depth(b) < compared_depth(a));
        PPSLL_COUNT(work_comparisons += (a_left > 0u && b_left > 0u && b != 0u) ? 1u : 0u);
        if (take_b) {
          taken = b;
          b = next_node(b);
          --b_left;
        } else {
          taken = a;
          a = next_node(a);
          --a_left;
        }
        if (merged_tail == 0u) merged_head = taken;
        else set_next(merged_tail, taken);
        PPSLL_COUNT(++work_relinks; if (width == 1u) ++work_merge_length);
        merged_tail = taken;
      }
      rest = b;
    }
    set_next(merged_tail, 0u);
    head = merged_head;
    if (merges <= 1u) return head;
  }
  return head;
}

// The invocation's tally, added once per list.
void ppsll_work_flush(uint length, bool in_place) {
#if WORK_COUNTING
  work_sample(list_length, length);
  work_add(bytes_loaded_heads, 4u);
  work_add(bytes_stored_heads, in_place ? 4u : 0u);
  work_add(atomic_add, in_place ? 1u : 0u);
  work_add(bytes_loaded_nodes, 4u * work_node_loads);
  work_add(bytes_stored_nodes, 4u * work_node_stores);
  work_add(bytes_loaded_nodes_compared, 4u * work_compared_loads);
  work_add(comparisons, work_comparisons);
  work_add(moves, work_relinks);
#endif
}

void main() {
  // Every invocation of the dispatch, those past the last pixel included: one add per group.
  if (gl_LocalInvocationIndex == 0u) work_add(invocations, gl_WorkGroupSize.x);
  const uint pixel = linear_invocation_index();
  if (pixel >= LDM_HEADS_TOTAL) return;
  const uint head = data[pixel];
  // Lists are acyclic by construction (every node is pushed once), so the walks end.
  uint count = 0u;
  uint node = head;
  for (; node != 0u && count < LDM_SORT_LOCAL; node = next_node(node))
    sort_local[count++] = depth_bits(node);
  if (node != 0u) {  // longer than the local array
    data[pixel] = merge_sort_list(head);
    atomicCounterIncrement(lists_sorted_in_place);
    PPSLL_COUNT(ppsll_work_flush(work_merge_length, true));
    return;
  }
  insertion_sort_local(count);
  const uint length = count;
  count = 0u;
  for (node = head; node != 0u; node = next_node(node)) {
    data[list_depth_slot(node)] = sort_local[count++];
    PPSLL_COUNT(++work_node_stores);
  }
  ppsll_work_flush(length, false);
}
