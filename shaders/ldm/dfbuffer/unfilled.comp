// DF-buffer check after a build (stats(), never timed): the storing pass counts every
// pixel's count back down to 0, so what remains in count[p] is slots of p's range that no
// fragment filled (the storing pass saw fewer fragments than the count pass). Their depths
// are stale; their number goes to df_unfilled_slots.
layout(local_size_x = 64) in;

#include "ldm/common/compute_grid.glsl"
#include "ldm/dfbuffer/layout.glsl"

layout(std430, binding = DF_COUNTS_BINDING) readonly restrict buffer DfCounts {
  uint df_counts[];
};
layout(std430, binding = LDM_STRUCTURE_BINDING3) restrict buffer DfCheck {
  uint df_check_counters[3];
  uint df_unfilled_slots;
};

void main() {
  const uint pixel = linear_invocation_index();
  if (pixel >= LDM_HEADS_TOTAL) return;
  // A count below 0 (more fragments than counted) wrapped; those were counted as lost.
  const int remaining = int(df_counts[pixel]);
  if (remaining > 0) atomicAdd(df_unfilled_slots, uint(remaining));
}
