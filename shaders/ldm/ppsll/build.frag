// PPSLL fragment storing (thesis §3.4.1, Listing 2): every fragment allocates a node with
// the atomic counter, stores its depth there, and pushes the node onto the front of its
// pixel's list with atomicExchange on the head. The lists come out in arbitrary order; the
// sort pass (sort.comp) orders them. A node past LDM_NODE_CAPACITY is not written: the host
// compares the counter with the capacity and records the overflow.
// Work counted (Ppsll::work_counters(), all deterministic): the node counter's increment and
// the exchange on the head, one each per fragment; the node's depth and next index stored.
#include "ldm/ldm_fragment.glsl"
#include "ldm/common/list_nodes.glsl"

layout(std430, binding = LDM_STRUCTURE_BINDING0) coherent restrict buffer PpsllData {
  uint data[];
};
layout(binding = LDM_COUNTER_BINDING, offset = 0) uniform atomic_uint node_counter;

void main() {
  LDM_SKIP_HELPER_INVOCATIONS;
  const uint pixel = ldm_fragment_pixel();
  // Step (a): a unique node; index 0 is reserved for "end of list".
  const uint node = atomicCounterIncrement(node_counter) + 1u;
  work_add(atomic_add, 1u);
  if (node > LDM_NODE_CAPACITY) return;
  // Step (b): the node is this invocation's alone, so plain writes suffice.
  data[list_depth_slot(node)] = floatBitsToUint(v_depth);
  // Steps (c) and (d): become the head; the old head is the new node's successor. Nothing
  // walks the lists during this pass, so the brief window before `next` is set is harmless.
  data[list_next_slot(node)] = atomicExchange(data[pixel], node);
  work_add(atomic_exchange, 1u);
  work_add(bytes_stored_nodes, 8u);
}
