// PPFLA query API (see common/ldm_query_api.glsl): the pixel's first min(count, k) entries,
// sorted by the sort pass.
// Work counted (Ppfla::query_work_counters(), deterministic): one query is one ldm_begin or
// ldm_next; its slots_scanned are the array slots it moves the cursor over to the pixel's
// next entry (1; 0 past the last, which the count tells without reading the array). Bytes
// are counted where they are read: the count in ldm_begin, an entry in ldm_depth.
// Kept repetition: the same range cursor as ldm/dfbuffer/query.glsl's, over this structure's
// own buffers and tallies; GLSL has no templates (docs/design/architecture.md).
#include "common/ldm_query_api.glsl"
#include "common/work_counters.glsl"
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

WORK_TALLY(ppfla_counts_bytes)
WORK_TALLY(ppfla_entries_bytes)
WORK_SAMPLE_TALLY(ppfla_slots_scanned)

LdmCursor ldm_begin(uint pixel) {
  const uint base = fa_entry(pixel, 0u);
  const LdmCursor c = LdmCursor(base, base + min(ppfla_counts[pixel], FA_K));
  work_tally(ppfla_counts_bytes, 4u);
  work_sample_tally(ppfla_slots_scanned, slots_scanned, c.entry < c.end ? 1u : 0u);
  return c;
}
bool ldm_valid(LdmCursor c) { return c.entry < c.end; }
float ldm_depth(LdmCursor c) {
  work_tally(ppfla_entries_bytes, 4u);
  return uintBitsToFloat(ppfla_entries[c.entry]);
}
LdmCursor ldm_next(LdmCursor c) {
  const LdmCursor next = LdmCursor(c.entry + 1u, c.end);
  work_sample_tally(ppfla_slots_scanned, slots_scanned, next.entry < next.end ? 1u : 0u);
  return next;
}
void ldm_work_flush() {
  work_add_tally(bytes_loaded_counts, ppfla_counts_bytes);
  work_add_tally(bytes_loaded_entries, ppfla_entries_bytes);
  work_sample_flush(slots_scanned, ppfla_slots_scanned);
}
