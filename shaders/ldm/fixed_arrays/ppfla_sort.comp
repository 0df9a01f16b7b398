// PPFLA "Sorting" (thesis §3.2.6): one invocation per LDM pixel sorts the pixel's
// min(count, k) entries in place by ascending depth. The thesis names bubble sort; insertion
// sort does the same job with fewer writes, and the arrays are short (k is the scene's depth
// complexity). Entries are moved as raw bits so the stored floats stay bit-exact.
layout(local_size_x = 64) in;

#include "ldm/fixed_arrays/fixed_array.glsl"

layout(std430, binding = LDM_STRUCTURE_BINDING0) restrict buffer PpflaEntries {
  uint ppfla_entries[];
};
layout(std430, binding = LDM_STRUCTURE_BINDING1) readonly restrict buffer PpflaCounts {
  uint ppfla_counts[];
};

void main() {
  const uint pixel = gl_GlobalInvocationID.y * (gl_NumWorkGroups.x * 64u) + gl_GlobalInvocationID.x;
  if (pixel >= LDM_HEADS_TOTAL) return;
  const uint count = min(ppfla_counts[pixel], FA_K);
  const uint base = fa_entry(pixel, 0u);
  for (uint i = 1u; i < count; ++i) {
    const uint bits = ppfla_entries[base + i];
    const float depth = uintBitsToFloat(bits);
    uint j = i;
    for (; j > 0u && uintBitsToFloat(ppfla_entries[base + j - 1u]) > depth; --j)
      ppfla_entries[base + j] = ppfla_entries[base + j - 1u];
    ppfla_entries[base + j] = bits;
  }
}
