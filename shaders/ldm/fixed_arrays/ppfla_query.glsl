// PPFLA query API (see common/ldm_query_api.glsl): the pixel's first min(count, k) entries,
// sorted by the sort pass.
#include "common/ldm_query_api.glsl"
#include "ldm/fixed_arrays/fixed_array.glsl"

layout(std430, binding = LDM_STRUCTURE_BINDING0) readonly restrict buffer PpflaEntries {
  uint ppfla_entries[];
};
layout(std430, binding = LDM_STRUCTURE_BINDING1) readonly restrict buffer PpflaCounts {
  uint ppfla_counts[];
};

struct LdmCursor {
  uint entry;  // index into ppfla_entries
  uint end;    // one past the pixel's last stored entry
};

LdmCursor ldm_begin(uint pixel) {
  const uint base = fa_entry(pixel, 0u);
  return LdmCursor(base, base + min(ppfla_counts[pixel], FA_K));
}
bool ldm_valid(LdmCursor c) { return c.entry < c.end; }
float ldm_depth(LdmCursor c) { return uintBitsToFloat(ppfla_entries[c.entry]); }
LdmCursor ldm_next(LdmCursor c) { return LdmCursor(c.entry + 1u, c.end); }
