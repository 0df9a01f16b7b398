// HA-buffer query API (see common/ldm_query_api.glsl): pixel p's entries are at slots
// h(p, a) for ages a = 0 .. ha_age_counts[p] - 1, in ascending depth (ha_keys.glsl). A slot
// whose entry has another age belongs to another pixel (age equivalence) and is skipped.
//
// Work counted (HaBuffer::query_work_counters()): one query is one ldm_begin or ldm_next, the
// seek to the pixel's next entry; its hash_probes are the slots it read (ha_probe()). The
// table's layout depends only on how many fragments each pixel has, not on the order they
// arrived (Robin Hood by age is history independent: docs/reference/work-counters.md), so
// the probes are deterministic.
#if HA_KEY_BITS == 64
#extension GL_ARB_gpu_shader_int64 : require
#endif
#include "common/ldm_query_api.glsl"
#include "common/work_counters.glsl"
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

#if WORK_COUNTING
uint ha_query_probes = 0u;  // slots read by the running seek
#endif
WORK_TALLY(ha_probes_read)
WORK_TALLY(ha_age_table_bytes)
WORK_SAMPLE_TALLY(ha_hash_probes)

// One probe: the key in pixel p's age-a slot.
HaKey ha_probe(uint pixel, uint age) {
  LDM_COUNT_QUERY_STEP();
#if WORK_COUNTING
  ++ha_query_probes;
#endif
  return ha_table[ha_slot(pixel, age)];
}

// The first age from c.age on whose slot holds this pixel's entry.
LdmCursor ha_seek(LdmCursor c) {
#if WORK_COUNTING
  ha_query_probes = 0u;
#endif
  for (; c.age < c.end; ++c.age) {
    c.key = ha_probe(c.pixel, c.age);
    if (ha_key_age(c.key) == c.age) break;
  }
  work_sample_tally(ha_hash_probes, hash_probes, ha_query_probes);
  work_tally(ha_probes_read, ha_query_probes);
  return c;
}

LdmCursor ldm_begin(uint pixel) {
  work_tally(ha_age_table_bytes, 4u);
  return ha_seek(LdmCursor(pixel, 0u, ha_age_counts[pixel], HA_EMPTY_KEY));
}
bool ldm_valid(LdmCursor c) { return c.age < c.end; }
float ldm_depth(LdmCursor c) { return ha_key_depth(c.key); }
LdmCursor ldm_next(LdmCursor c) {
  ++c.age;
  return ha_seek(c);
}
void ldm_work_flush() {
#if WORK_COUNTING
  work_add(bytes_loaded_table, ha_probes_read * uint(HA_KEY_BITS / 8));
  work_add(bytes_loaded_ha_offsets, ha_probes_read * 4u);  // o_a of each probed slot
  ha_probes_read = 0u;
#endif
  work_add_tally(bytes_loaded_age_table, ha_age_table_bytes);
  work_sample_flush(hash_probes, ha_hash_probes);
}
