// PSPPFLA query API (see common/ldm_query_api.glsl): the pixel's entries up to the first
// empty one (or k); sorted during construction.
// Work counted (Psppfla::query_work_counters(), deterministic): one query is one ldm_begin or
// ldm_next; its slots_scanned are the array slots it read to find the pixel's next entry (1,
// the first empty one past the last included; 0 once past k).
#include "common/ldm_query_api.glsl"
#include "common/work_counters.glsl"
#include "ldm/fixed_arrays/fixed_array.glsl"
#include "ldm/fixed_arrays/ordered_depth.glsl"

layout(std430, binding = LDM_STRUCTURE_BINDING0) readonly restrict buffer PsppflaEntries {
  uint psppfla_entries[];
};

struct LdmCursor {
  uint entry;    // index into psppfla_entries
  uint end;      // one past the pixel's last entry
  uint ordered;  // the entry's value; 0xFFFFFFFF once past the last stored depth
};

WORK_TALLY(psppfla_entries_bytes)
WORK_SAMPLE_TALLY(psppfla_slots_scanned)

LdmCursor psppfla_cursor(uint entry, uint end) {
  work_sample_tally(psppfla_slots_scanned, slots_scanned, entry < end ? 1u : 0u);
  work_tally(psppfla_entries_bytes, entry < end ? 4u : 0u);
  return LdmCursor(entry, end, entry < end ? psppfla_entries[entry] : 0xFFFFFFFFu);
}

LdmCursor ldm_begin(uint pixel) {
  const uint base = fa_entry(pixel, 0u);
  return psppfla_cursor(base, base + FA_K);
}
bool ldm_valid(LdmCursor c) { return c.ordered != 0xFFFFFFFFu; }
float ldm_depth(LdmCursor c) { return depth_from_ordered_bits(c.ordered); }
LdmCursor ldm_next(LdmCursor c) { return psppfla_cursor(c.entry + 1u, c.end); }
void ldm_work_flush() {
  work_add_tally(bytes_loaded_entries, psppfla_entries_bytes);
  work_sample_flush(slots_scanned, psppfla_slots_scanned);
}
