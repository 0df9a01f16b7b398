// The query API (common/ldm_query_api.glsl) of the linked-list structures, PPSLL (after its
// sort pass) and PSPPSLL: follow next indices from the pixel's head.
// Work counted (Psppsll/Ppsll::query_work_counters(), deterministic: the lists are sorted):
// one query is one ldm_begin or ldm_next, and its nodes_visited the nodes it moved the
// cursor onto (1, or 0 at the list's end); bytes where they are read: the head in
// ldm_begin, a node's next index in ldm_next, its depth in ldm_depth.
#include "common/ldm_query_api.glsl"
#include "common/work_counters.glsl"
#include "ldm/common/list_nodes.glsl"

layout(std430, binding = LDM_STRUCTURE_BINDING0) readonly restrict buffer ListData {
  uint data[];
};

struct LdmCursor {
  uint node;  // 0 past the end
};

WORK_TALLY(list_heads_bytes)
WORK_TALLY(list_nodes_bytes)
WORK_SAMPLE_TALLY(list_nodes_visited)

LdmCursor ldm_begin(uint pixel) {
  const LdmCursor c = LdmCursor(data[pixel]);
  work_tally(list_heads_bytes, 4u);
  work_sample_tally(list_nodes_visited, nodes_visited, c.node != 0u ? 1u : 0u);
  return c;
}
bool ldm_valid(LdmCursor c) { return c.node != 0u; }
float ldm_depth(LdmCursor c) {
  work_tally(list_nodes_bytes, 4u);
  return uintBitsToFloat(data[list_depth_slot(c.node)]);
}
LdmCursor ldm_next(LdmCursor c) {
  const LdmCursor next = LdmCursor(data[list_next_slot(c.node)]);
  work_tally(list_nodes_bytes, 4u);
  work_sample_tally(list_nodes_visited, nodes_visited, next.node != 0u ? 1u : 0u);
  return next;
}
void ldm_work_flush() {
  work_add_tally(bytes_loaded_heads, list_heads_bytes);
  work_add_tally(bytes_loaded_nodes, list_nodes_bytes);
  work_sample_flush(nodes_visited, list_nodes_visited);
}
