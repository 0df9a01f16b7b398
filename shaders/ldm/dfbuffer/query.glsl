// DF-buffer query API (see common/ldm_query_api.glsl): a cursor walks the pixel's
// contiguous, sorted range of the depth array (layout: ldm/dfbuffer/layout.glsl).
// Work counted (DfBuffer::query_work_counters(), deterministic: the ranges are sorted): one
// query is one ldm_begin or ldm_next, and its nodes_visited the entries it moved the cursor
// onto (1, or 0 past the range's end); bytes where they are read: the two offsets in
// ldm_begin, a depth in ldm_depth.
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

LdmCursor ldm_begin(uint pixel) {
  const LdmCursor c = LdmCursor(df_offsets[pixel], min(df_offsets[pixel + 1u], LDM_DF_CAPACITY));
  work_add(bytes_loaded_offsets, 8u);
  work_sample(nodes_visited, c.index < c.end ? 1u : 0u);
  return c;
}
bool ldm_valid(LdmCursor c) { return c.index < c.end; }
float ldm_depth(LdmCursor c) {
  work_add(bytes_loaded_depths, 4u);
  return uintBitsToFloat(df_depths[c.index]);
}
LdmCursor ldm_next(LdmCursor c) {
  const LdmCursor next = LdmCursor(c.index + 1u, c.end);
  work_sample(nodes_visited, next.index < next.end ? 1u : 0u);
  return next;
}
