// DF-buffer query API (see common/ldm_query_api.glsl): a cursor walks the pixel's
// contiguous, sorted range of the depth array (layout: ldm/dfbuffer/layout.glsl).
#include "common/ldm_query_api.glsl"
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
  return LdmCursor(df_offsets[pixel], min(df_offsets[pixel + 1u], LDM_DF_CAPACITY));
}
bool ldm_valid(LdmCursor c) { return c.index < c.end; }
float ldm_depth(LdmCursor c) { return uintBitsToFloat(df_depths[c.index]); }
LdmCursor ldm_next(LdmCursor c) { return LdmCursor(c.index + 1u, c.end); }
