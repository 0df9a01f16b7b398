// One level of the DF-buffer's prefix sum (ldm_impls/dfbuffer/prefix_sum.h): workgroup g
// writes the exclusive scan of its block of SCAN_GROUP_SIZE * SCAN_PER_INVOCATION values
// and the block's sum to scan_block_sums[g].
//   1. the block is staged in shared memory with coalesced reads (values past
//      scan_input_count read as 0);
//   2. each invocation scans its SCAN_PER_INVOCATION consecutive values serially;
//   3. the invocations' sums are scanned work-efficiently (Blelloch's up-sweep and
//      down-sweep, O(n) additions, 2 log2(n) barriers);
//   4. the results go back through shared memory to coalesced writes of scan_count values.
// Input and output may be one buffer (block sums scanned in place): each block reads all
// of its values before it writes any, and touches no other block's.
// Work counted (DfBuffer::work_counters(), "prefix_sum", deterministic): invocations and the
// bytes read and written, per buffer: level 0 reads the counts and writes the offsets,
// higher levels scan the block sums in place; every level writes its block sums.
layout(local_size_x = SCAN_GROUP_SIZE) in;

#include "common/work_counters.glsl"
#include "ldm/common/compute_grid.glsl"

const uint SCAN_BLOCK = SCAN_GROUP_SIZE * SCAN_PER_INVOCATION;

layout(std430, binding = LDM_STRUCTURE_BINDING0) readonly buffer ScanInput {
  uint scan_input[];
};
layout(std430, binding = LDM_STRUCTURE_BINDING1) writeonly buffer ScanOutput {
  uint scan_output[];
};
layout(std430, binding = LDM_STRUCTURE_BINDING2) writeonly restrict buffer ScanBlockSums {
  uint scan_block_sums[];
};

uniform uint scan_input_count;  // values to read; the rest of the block reads as 0
uniform uint scan_count;        // values to write
uniform uint scan_group_count;  // blocks of this level
#if WORK_COUNTING
uniform uint work_scan_level;  // the level scanned (PrefixSum::scan_level)
#endif

shared uint block_values[SCAN_BLOCK];
shared uint invocation_sums[SCAN_GROUP_SIZE];

// Exclusive scan of invocation_sums in place; returns the sum of all of them to invocation 0.
uint scan_invocation_sums(uint t) {
  for (uint stride = 1u; stride < SCAN_GROUP_SIZE; stride <<= 1) {  // up-sweep
    barrier();
    const uint right = (t + 1u) * stride * 2u - 1u;
    if (right < SCAN_GROUP_SIZE) invocation_sums[right] += invocation_sums[right - stride];
  }
  barrier();
  uint total = 0u;
  if (t == 0u) {  // the root holds the total; clearing it starts the down-sweep
    total = invocation_sums[SCAN_GROUP_SIZE - 1u];
    invocation_sums[SCAN_GROUP_SIZE - 1u] = 0u;
  }
  for (uint stride = SCAN_GROUP_SIZE >> 1; stride > 0u; stride >>= 1) {  // down-sweep
    barrier();
    const uint right = (t + 1u) * stride * 2u - 1u;
    if (right < SCAN_GROUP_SIZE) {
      const uint left_sum = invocation_sums[right - stride];
      invocation_sums[right - stride] = invocation_sums[right];
      invocation_sums[right] += left_sum;
    }
  }
  barrier();
  return total;
}

void main() {
  if (gl_LocalInvocationIndex == 0u) work_add(invocations, gl_WorkGroupSize.x);
  const uint group = linear_workgroup_index();
  if (group >= scan_group_count) return;  // the grid's last row overshoots; whole groups leave
#if WORK_COUNTING
  uint work_loads = 0u, work_stores = 0u;
#endif
  const uint t = gl_LocalInvocationID.x;
  const uint block_first = group * SCAN_BLOCK;

  for (uint i = 0u; i < SCAN_PER_INVOCATION; ++i) {
    const uint at = block_first + i * SCAN_GROUP_SIZE + t;
    block_values[i * SCAN_GROUP_SIZE + t] = at < scan_input_count ? scan_input[at] : 0u;
#if WORK_COUNTING
    if (at < scan_input_count) ++work_loads;
#endif
  }
  barrier();

  uint running = 0u;
  for (uint i = 0u; i < SCAN_PER_INVOCATION; ++i) {
    const uint value = block_values[t * SCAN_PER_INVOCATION + i];
    block_values[t * SCAN_PER_INVOCATION + i] = running;
    running += value;
  }
  invocation_sums[t] = running;

  const uint block_total = scan_invocation_sums(t);
  const uint before = invocation_sums[t];
  for (uint i = 0u; i < SCAN_PER_INVOCATION; ++i)
    block_values[t * SCAN_PER_INVOCATION + i] += before;
  barrier();

  for (uint i = 0u; i < SCAN_PER_INVOCATION; ++i) {
    const uint at = block_first + i * SCAN_GROUP_SIZE + t;
    if (at < scan_count) scan_output[at] = block_values[i * SCAN_GROUP_SIZE + t];
#if WORK_COUNTING
    if (at < scan_count) ++work_stores;
#endif
  }
  if (t == 0u) scan_block_sums[group] = block_total;
#if WORK_COUNTING
  if (work_scan_level == 0u) {
    work_add(bytes_loaded_counts, 4u * work_loads);
    work_add(bytes_stored_offsets, 4u * work_stores);
  } else {
    work_add(bytes_loaded_scan_block_sums, 4u * work_loads);
    work_add(bytes_stored_scan_block_sums, 4u * work_stores);
  }
  if (t == 0u) work_add(bytes_stored_scan_block_sums, 4u);
#endif
}
