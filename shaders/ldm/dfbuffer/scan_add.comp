// The uniform add of the DF-buffer's prefix sum (ldm_impls/dfbuffer/prefix_sum.h): every
// value of block g gains the scanned sum of the blocks before it, scan_block_offsets[g].
layout(local_size_x = SCAN_GROUP_SIZE) in;

#include "ldm/common/compute_grid.glsl"

const uint SCAN_BLOCK = SCAN_GROUP_SIZE * SCAN_PER_INVOCATION;

layout(std430, binding = LDM_STRUCTURE_BINDING0) restrict buffer ScanValues {
  uint scan_values[];
};
layout(std430, binding = LDM_STRUCTURE_BINDING1) readonly restrict buffer ScanBlockOffsets {
  uint scan_block_offsets[];
};

uniform uint scan_count;
uniform uint scan_group_count;

void main() {
  const uint group = linear_workgroup_index();
  if (group == 0u || group >= scan_group_count) return;  // block 0 adds nothing
  const uint offset = scan_block_offsets[group];
  for (uint i = 0u; i < SCAN_PER_INVOCATION; ++i) {
    const uint at = group * SCAN_BLOCK + i * SCAN_GROUP_SIZE + gl_LocalInvocationID.x;
    if (at < scan_count) scan_values[at] += offset;
  }
}
