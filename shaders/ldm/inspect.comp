// Walks every pixel's list through the query API, the same way passes do, to check a built
// structure (validation after every measured build) or to dump its lists (tests).
//   LDM_INSPECT_DUMP 0: per pixel length, and totals: nodes, unsorted pixels, pixels that
//                       reach LDM_MAX_LIST_LENGTH, checksum of every list's depth sequence.
//   LDM_INSPECT_DUMP 1: writes the depths of pixel g at inspect_offsets[g - first].
layout(local_size_x = 64) in;

#include "common/ldm_query_api.glsl"
#include "ldm/common/compute_grid.glsl"

layout(std430, binding = LDM_VALIDATION_BINDING) restrict buffer Inspect {
  uint inspect_totals[8];  // 0 nodes, 1 unsorted pixels, 2 over-long pixels, 3-4 checksums
  uint inspect_data[];     // lengths (mode 0) or offsets then depths (mode 1)
};

uniform uint inspect_first_pixel;
uniform uint inspect_pixel_count;
uniform uint inspect_store_lengths;  // mode 0: also write per-pixel lengths

uint mix_hash(uint h, uint v) {
  h ^= v;
  h *= 0x01000193u;  // FNV-1a step on 32-bit words
  h ^= h >> 15;
  return h;
}

void main() {
  const uint local = linear_invocation_index();
  if (local >= inspect_pixel_count) return;
  const uint pixel = inspect_first_pixel + local;
  uint length = 0u;
#if LDM_INSPECT_DUMP
  uint out_at = inspect_data[local];
#else
  bool sorted = true;
  float previous = -1.0 / 0.0;
  uint hash = 0x811c9dc5u;
#endif
  for (LdmCursor c = ldm_begin(pixel); ldm_valid(c) && length <= LDM_MAX_LIST_LENGTH;
       c = ldm_next(c)) {
    const float depth = ldm_depth(c);
#if LDM_INSPECT_DUMP
    inspect_data[inspect_pixel_count + out_at + length] = floatBitsToUint(depth);
#else
    sorted = sorted && depth >= previous;
    previous = depth;
    hash = mix_hash(hash, floatBitsToUint(depth));
#endif
    ++length;
  }
#if !LDM_INSPECT_DUMP
  if (inspect_store_lengths != 0u) inspect_data[local] = length;
  atomicAdd(inspect_totals[0], length);
  if (!sorted) atomicAdd(inspect_totals[1], 1u);
  if (length > LDM_MAX_LIST_LENGTH) atomicAdd(inspect_totals[2], 1u);
  if (length > 0u) {
    atomicAdd(inspect_totals[3], mix_hash(hash, pixel));
    atomicXor(inspect_totals[4], mix_hash(hash * 0x9e3779b9u, pixel + 0x68bc21ebu));
  }
#endif
}
