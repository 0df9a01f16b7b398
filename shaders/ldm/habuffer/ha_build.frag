// HA-buffer construction (thesis §3.2.13): one geometry pass inserting every fragment into
// the hash table H with Robin Hood collision resolution by atomicMax on age-and-depth keys
// (ha_keys.glsl). The carried entry starts as the fragment at age 0 and tries its slot
// h(p, a):
//   - atomicMax leaves the larger key there. If that is the carried one and the slot was
//     empty, the insertion is done; if it evicted an entry, that entry (younger, or the same
//     pixel's farther fragment) is carried on instead, its pixel recovered by age equivalence.
//   - Otherwise (an older entry, the same pixel's nearer fragment, or an equal key) the
//     carried entry stays the same.
// Either way the carried entry then ages by one and tries its next slot. An entry that would
// age past HA_MAX_AGE cannot be stored (its age no longer fits) and is dropped and counted.
// ha_age_counts[p] (atomicMax of age + 1 over p's placements) lets queries stop at the
// highest age pixel p reached instead of walking every age.
//
// HA_STOP_WHEN_FULL (previous_frame's first build, from a guessed table; habuffer.h): every
// fragment first takes a ticket from `attempted`; a fragment whose ticket is >= HA_STOP_TICKET
// (|H| * load_factor, what the table is sized for) proves that the table this scene needs
// is larger, so the driver will rebuild it from the counts. It then stores nothing and
// returns (counted on the host as attempted - HA_STOP_TICKET, lost), instead of probing a
// table past its load factor: near full, every insertion walks (and evicts along) up to
// HA_MAX_AGE + 1 slots before an entry is dropped.
//
// Work counted in the counting replay (HaBuffer::work_counters(); arrival-dependent but the
// tickets: an insertion's chain depends on what arrived before it): per fragment, tallied in locals and
// added once when its insertion ends (ha_count_insertion(), after ha_insert() returns: not
// at the returns inside its loop, where a SIMD rasteriser would run the counting's atomics,
// masked, on every iteration).
#if HA_KEY_BITS == 64
#extension GL_ARB_gpu_shader_int64 : require
#extension GL_NV_shader_atomic_int64 : require
#endif
#include "ldm/ldm_fragment.glsl"
#include "ldm/habuffer/ha_keys.glsl"

layout(std430, binding = LDM_STRUCTURE_BINDING0) restrict buffer HaTable { HaKey ha_table[]; };
layout(std430, binding = LDM_STRUCTURE_BINDING2) restrict buffer HaAgeCounts {
  uint ha_age_counts[];  // per pixel of every view: highest age of its entries + 1
};
layout(binding = LDM_COUNTER_BINDING, offset = 0) uniform atomic_uint dropped_max_age;
layout(binding = LDM_COUNTER_BINDING, offset = 4) uniform atomic_uint aborted_insertions;
#if HA_STOP_WHEN_FULL
layout(binding = LDM_COUNTER_BINDING, offset = 8) uniform atomic_uint attempted;
#endif

#if WORK_COUNTING
const uint HA_KEY_BYTES = uint(HA_KEY_BITS / 8);
uint ha_probes = 0u;     // atomicMax on the table: one per slot tried
uint ha_evictions = 0u;  // entries the carried one took a slot from (carried on instead)
uint ha_age_bumps = 0u;  // times the carried entry aged by one to try its next slot
uint ha_age_raises = 0u; // atomicMax on ha_age_counts (one per placement)
uint ha_tickets = 0u;     // atomic counter increments of the ticket (previous_frame's guess)
uint ha_losses = 0u;      // atomic counter increments of a dropped or aborted insertion

// What one fragment's insertion did, added once when it ends.
void ha_count_insertion() {
  work_sample(hash_probes, ha_probes);
#if HA_KEY_BITS == 64
  work_add(atomic_max_64, ha_probes);
  work_add(atomic_max, ha_age_raises);
#else
  work_add(atomic_max, ha_probes + ha_age_raises);
#endif
  work_add(atomic_max_failed, ha_probes - ha_age_raises);  // left the slot's key as it was
  work_add(evictions, ha_evictions);
  work_add(age_bumps, ha_age_bumps);
  work_add(atomic_add, ha_tickets);
  work_add(atomic_add_on_loss, ha_losses);
  // An atomic reads and writes its word: counted as loaded and stored.
  work_add(bytes_loaded_table, ha_probes * HA_KEY_BYTES);
  work_add(bytes_stored_table, ha_probes * HA_KEY_BYTES);
  work_add(bytes_loaded_age_table, ha_age_raises * 4u);
  work_add(bytes_stored_age_table, ha_age_raises * 4u);
  // o_a: once per slot tried (ha_slot) and once per eviction (ha_pixel_of).
  work_add(bytes_loaded_ha_offsets, (ha_probes + ha_evictions) * 4u);
}
#define HA_COUNT(statement) statement
#define HA_INSERTION_ENDS() ha_count_insertion()
#else
#define HA_COUNT(statement)
#define HA_INSERTION_ENDS()
#endif

// One fragment's insertion: placed, evicting along its chain, or dropped.
void ha_insert() {
#if HA_STOP_WHEN_FULL
  HA_COUNT(++ha_tickets);
  if (atomicCounterIncrement(attempted) >= HA_STOP_TICKET) return;
#endif
  uint pixel = ldm_fragment_pixel();
  uint age = 0u;
  HaKey key = ha_key(0u, ha_depth_bits(v_depth));
  // Robin Hood chains are short; the bound only keeps a faulty device from hanging. An
  // insertion that reaches it loses its carried entry and is counted.
  for (uint step = 0u; step < HA_MAX_INSERT_STEPS; ++step) {
    const uint slot = ha_slot(pixel, age);
    const HaKey previous = atomicMax(ha_table[slot], key);
    HA_COUNT(++ha_probes);
    if (previous < key) {
      atomicMax(ha_age_counts[pixel], age + 1u);
      HA_COUNT(++ha_age_raises);
      if (previous == HA_EMPTY_KEY) return;
      HA_COUNT(++ha_evictions);
      key = previous;
      age = ha_key_age(previous);
      pixel = ha_pixel_of(slot, age);
    }
    if (age == HA_MAX_AGE) {
      atomicCounterIncrement(dropped_max_age);
      HA_COUNT(++ha_losses);
      return;
    }
    ++age;
    HA_COUNT(++ha_age_bumps);
    key = ha_key_aged(key, age);
  }
  atomicCounterIncrement(aborted_insertions);
  HA_COUNT(++ha_losses);
}

void main() {
  LDM_SKIP_HELPER_INVOCATIONS;
  ha_insert();
  HA_INSERTION_ENDS();
}
