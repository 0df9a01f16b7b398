// DF-buffer step 1, fragment counting (thesis §3.2.10): per-pixel atomic counts.
// Work counted (DfBuffer::work_counters(), "count"): one atomicAdd per fragment.
#include "ldm/ldm_fragment.glsl"
#include "ldm/dfbuffer/layout.glsl"

layout(std430, binding = DF_COUNTS_BINDING) restrict buffer DfCounts { uint df_counts[]; };

void main() {
  LDM_SKIP_HELPER_INVOCATIONS;
  atomicAdd(df_counts[ldm_fragment_pixel()], 1u);
  work_add(atomic_add, 1u);
}
