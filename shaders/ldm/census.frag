// Counting pass: fragments per LDM pixel over all views. Used to size every structure from
// what the scene needs (thesis §3.4.4 sized pools from a heuristic; we count instead).
#include "ldm/ldm_fragment.glsl"

layout(std430, binding = LDM_CENSUS_BINDING) restrict buffer Census { uint census_counts[]; };

void main() {
  LDM_SKIP_HELPER_INVOCATIONS;
  atomicAdd(census_counts[ldm_fragment_pixel()], 1u);
}
