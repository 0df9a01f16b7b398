// PSPPSLL query API (see common/ldm_query_api.glsl): follow next indices from the head.
#include "common/ldm_query_api.glsl"

layout(std430, binding = LDM_STRUCTURE_BINDING0) readonly restrict buffer PsppsllData {
  uint data[];
};

struct LdmCursor {
  uint node;  // 0 past the end
};

LdmCursor ldm_begin(uint pixel) { return LdmCursor(data[pixel]); }
bool ldm_valid(LdmCursor c) { return c.node != 0u; }
float ldm_depth(LdmCursor c) { return uintBitsToFloat(data[LDM_HEADS_TOTAL + 2u * (c.node - 1u) + 1u]); }
LdmCursor ldm_next(LdmCursor c) { return LdmCursor(data[LDM_HEADS_TOTAL + 2u * (c.node - 1u)]); }
