// PPSLL sorting pass (thesis §3.2.8 "Sorting", §3.3.3): one invocation per LDM pixel of all
// views. The list's depths are copied into the local array, insertion-sorted, and written
// back along the same nodes in ascending order: the links stay, the values move, so the
// sorted lists are read by the unchanged list query. A list longer than LDM_SORT_LOCAL is
// insertion-sorted in place through its nodes and counted.
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

// Insertion sort on the list itself: the nodes before `node` are sorted; its depth is
// inserted by rotating the depths from the first larger one up to `node` one place along
// the list. O(n^2) node fetches from storage memory: the slow path that a large enough K
// avoids. Depths move as bits (see post_sort.glsl).
void sort_list_in_place(uint head) {
  for (uint node = next_node(head); node != 0u; node = next_node(node)) {
    uint carried = depth_bits(node);
    const float depth = uintBitsToFloat(carried);
    uint at = head;
    while (at != node && node_depth(at) <= depth) at = next_node(at);
    for (; at != node; at = next_node(at)) {
      const uint displaced = depth_bits(at);
      data[list_depth_slot(at)] = carried;
      carried = displaced;
    }
    data[list_depth_slot(node)] = carried;
  }
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
    sort_list_in_place(head);
    atomicCounterIncrement(lists_sorted_in_place);
    return;
  }
  insertion_sort_local(count);
  count = 0u;
  for (node = head; node != 0u; node = next_node(node))
    data[list_depth_slot(node)] = sort_local[count++];
}
