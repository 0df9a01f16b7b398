// PPSLL sorting pass (thesis §3.2.8 "Sorting", §3.3.3): one invocation per LDM pixel of all
// views. The list's depths are copied into the local array, insertion-sorted, and written
// back along the same nodes in ascending order: the links stay, the values move, so the
// sorted lists are read by the unchanged list query. A list longer than LDM_SORT_LOCAL is
// merge-sorted in place by relinking its nodes (counted).
layout(local_size_x = 64) in;

#include "ldm/common/compute_grid.glsl"
#include "ldm/common/list_nodes.glsl"
#include "ldm/common/post_sort.glsl"

layout(std430, binding = LDM_STRUCTURE_BINDING0) restrict buffer PpsllData {
  uint data[];
};
layout(binding = LDM_COUNTER_BINDING, offset = 4) uniform atomic_uint lists_sorted_in_place;

uint next_node(uint node) { return data[list_next_slot(node)]; }
uint depth_bits(uint node) { return data[list_depth_slot(node)]; }
float node_depth(uint node) { return uintBitsToFloat(depth_bits(node)); }

void set_next(uint node, uint next) { data[list_next_slot(node)] = next; }

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
                            (b_left > 0u && b != 0u && node_depth(b) < node_depth(a));
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

void main() {
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
    return;
  }
  insertion_sort_local(count);
  count = 0u;
  for (node = head; node != 0u; node = next_node(node))
    data[list_depth_slot(node)] = sort_local[count++];
}
