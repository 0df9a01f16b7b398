// Sum, maximum and number of non-empty items of a uint buffer
// (ldm_impls/common/uint_reduction.h), reduced per workgroup in shared memory so that one
// atomic per group and quantity reaches the result. An item is reduce_words_per_item
// consecutive words (2 for the HA-buffer's 64-bit keys): its value is its first word; it is
// empty when all its words equal reduce_empty (0, or PSPPFLA's empty entry). Sum and maximum
// are over the first words of non-empty items. Each invocation reduces REDUCE_ITEMS_PER_INVOCATION
// consecutive items in registers first, so shared-memory atomics stay few.
layout(local_size_x = 256) in;

#include "ldm/common/compute_grid.glsl"

layout(std430, binding = LDM_CENSUS_BINDING) readonly restrict buffer ReduceInput {
  uint reduce_input[];
};
layout(std430, binding = LDM_VALIDATION_BINDING) restrict buffer ReduceOutput {
  uint reduce_sum;
  uint reduce_max;
  uint reduce_nonzero;
};

uniform uint reduce_items;
uniform uint reduce_words_per_item;
uniform uint reduce_empty;

shared uint group_sum, group_max, group_nonzero;

void main() {
  if (gl_LocalInvocationIndex == 0u) {
    group_sum = 0u;
    group_max = 0u;
    group_nonzero = 0u;
  }
  barrier();
  uint sum = 0u, highest = 0u, nonempty_items = 0u;
  const uint begin = linear_invocation_index() * REDUCE_ITEMS_PER_INVOCATION;
  const uint end = min(begin + REDUCE_ITEMS_PER_INVOCATION, reduce_items);
  for (uint item = begin; item < end; ++item) {
    const uint first = item * reduce_words_per_item;
    const uint value = reduce_input[first];
    bool nonempty = value != reduce_empty;
    for (uint w = 1u; w < reduce_words_per_item; ++w)
      nonempty = nonempty || reduce_input[first + w] != reduce_empty;
    if (nonempty) {
      sum += value;
      highest = max(highest, value);
      ++nonempty_items;
    }
  }
  if (nonempty_items != 0u) {
    atomicAdd(group_sum, sum);
    atomicMax(group_max, highest);
    atomicAdd(group_nonzero, nonempty_items);
  }
  barrier();
  if (gl_LocalInvocationIndex == 0u) {
    if (group_sum != 0u) atomicAdd(reduce_sum, group_sum);
    if (group_max != 0u) atomicMax(reduce_max, group_max);
    if (group_nonzero != 0u) atomicAdd(reduce_nonzero, group_nonzero);
  }
}
