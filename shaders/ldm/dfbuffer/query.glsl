// DF-buffer query API (see common/ldm_query_api.glsl): a cursor walks the pixel's
// contiguous, sorted range of the depth array (layout: ldm/dfbuffer/layout.glsl).
// Work counted (DfBuffer::query_work_counters(), deterministic: the ranges are sorted): one
// query is one ldm_begin or ldm_next, and its nodes_visited the entries it moved the cursor
// onto (1, or 0 past the range's end); bytes where they are read: the two offsets in
// ldm_begin, a depth in ldm_depth.
// Kept repetition: the cursor over one contiguous range (ldm_valid, ldm_depth, ldm_next, the
// flush) stands again in ldm/fixed_arrays/ppfla_query.glsl over that structure's own buffers
// and tallies; GLSL has no templates (docs/design/architecture.md, repetition kept).
#include "common/ldm_query_api.glsl"
#include "common/work_counters.glsl"
#include "ldm/dfbuffer/layout.glsl"

layout(std430, binding = DF_OFFSETS_BINDING) readonly restrict buffer DfOffsets {
  uint df_offsets[];
};
layout(std430, binding = DF_DEPTHS_BINDING) readonly restrict buffer DfDepths {
  uint df_depths[];  // float bits
};

struct LdmCursor {
  uint index;  // slot in df_depths
  uint end;    // one past the pixel's last slot
};

WORK_TALLY(df_offsets_bytes)
WORK_TALLY(df_depths_bytes)
WORK_SAMPLE_TALLY(df_nodes_visited)

LdmCursor ldm_begin(uint pixel) {
  const LdmCursor c = LdmCursor(df_offsets[pixel], min(df_offsets[pixel + 1u], LDM_DF_CAPACITY));
  work_tally(df_offsets_bytes, 8u);
  work_sample_tally(df_nodes_visited, nodes_visited, c.index < c.end ? 1u : 0u);
  return c;
}
bool ldm_valid(LdmCursor c) { return c.index < c.end; }
float ldm_depth(LdmCursor c) {
  work_tally(df_depths_bytes, 4u);
  return uintBitsToFloat(df_depths[c.index]);
}
LdmCursor ldm_next(LdmCursor c) {
  const LdmCursor next = LdmCursor(c.index + 1u, c.end);
  work_sample_tally(df_nodes_visited, nodes_visited, next.index < next.end ? 1u : 0u);
  return next;
}
void ldm_work_flush() {
  work_add_tally(bytes_loaded_offsets, df_offsets_bytes);
  work_add_tally(bytes_loaded_depths, df_depths_bytes);
  work_sample_flush(nodes_visited, df_nodes_visited);
}
