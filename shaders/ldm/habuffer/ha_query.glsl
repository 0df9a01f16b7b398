// HA-buffer query API (see common/ldm_query_api.glsl): pixel p's entries are at slots
// h(p, a) for ages a = 0 .. ha_age_counts[p] - 1, in ascending depth (ha_keys.glsl). A slot
// whose entry has another age belongs to another pixel (age equivalence) and is skipped.
#if HA_KEY_BITS == 64
#extension GL_ARB_gpu_shader_int64 : require
#endif
#include "common/ldm_query_api.glsl"
#include "ldm/habuffer/ha_keys.glsl"

layout(std430, binding = LDM_STRUCTURE_BINDING0) readonly restrict buffer HaTable {
  HaKey ha_table[];
};
layout(std430, binding = LDM_STRUCTURE_BINDING2) readonly restrict buffer HaAgeCounts {
  uint ha_age_counts[];
};

struct LdmCursor {
  uint pixel;
  uint age;   // of the current entry; `end` once past the last
  uint end;   // the pixel's highest age + 1
  HaKey key;  // the current entry
};

// The first age from c.age on whose slot holds this pixel's entry.
LdmCursor ha_seek(LdmCursor c) {
  for (; c.age < c.end; ++c.age) {
    LDM_COUNT_QUERY_STEP();
    c.key = ha_table[ha_slot(c.pixel, c.age)];
    if (ha_key_age(c.key) == c.age) break;
  }
  return c;
}

LdmCursor ldm_begin(uint pixel) {
  return ha_seek(LdmCursor(pixel, 0u, ha_age_counts[pixel], HA_EMPTY_KEY));
}
bool ldm_valid(LdmCursor c) { return c.age < c.end; }
float ldm_depth(LdmCursor c) { return ha_key_depth(c.key); }
LdmCursor ldm_next(LdmCursor c) {
  ++c.age;
  return ha_seek(c);
}
