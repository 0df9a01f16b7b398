// The query API (common/ldm_query_api.glsl) of the linked-list structures, PPSLL (after its
// sort pass) and PSPPSLL: follow next indices from the pixel's head.
#include "common/ldm_query_api.glsl"
#include "ldm/common/list_nodes.glsl"

layout(std430, binding = LDM_STRUCTURE_BINDING0) readonly restrict buffer ListData {
  uint data[];
};

struct LdmCursor {
  uint node;  // 0 past the end
};

LdmCursor ldm_begin(uint pixel) { return LdmCursor(data[pixel]); }
bool ldm_valid(LdmCursor c) { return c.node != 0u; }
float ldm_depth(LdmCursor c) { return uintBitsToFloat(data[list_depth_slot(c.node)]); }
LdmCursor ldm_next(LdmCursor c) { return LdmCursor(data[list_next_slot(c.node)]); }
