// Walks pixels' lists through the query API, the same way passes do, to check a built
// structure (validation of builds) or to dump its lists (tests).
//   LDM_INSPECT_DUMP 0: per pixel length, and totals: nodes, unsorted pixels, pixels that
//                       reach LDM_MAX_LIST_LENGTH, checksum of every list's depth sequence;
//                       per 64-pixel block (one workgroup) a hash of its lists, which
//                       inspect_block_mode writes (a full check: the reference) or compares
//                       with the reference (a sampled check: 1 block in inspect_block_stride)
//   LDM_INSPECT_DUMP 1: writes the depths of pixel g at inspect_offsets[g - first].
layout(local_size_x = 64) in;

#include "common/ldm_query_api.glsl"
#include "ldm/common/compute_grid.glsl"

layout(std430, binding = LDM_VALIDATION_BINDING) restrict buffer Inspect {
  // 0 nodes, 1 unsorted pixels, 2 over-long pixels, 3-4 checksums, 5 changed blocks,
  // 6 pixels visited, 7 tied depths (a fragment stored at its predecessor's depth)
  uint inspect_totals[8];
  uint inspect_data[];     // lengths (mode 0) or offsets then depths (mode 1)
};

#if !LDM_INSPECT_DUMP
// One hash per 64-pixel block, indexed by (first pixel) / 64.
layout(std430, binding = LDM_INSPECT_BLOCKS_BINDING) restrict buffer InspectBlocks {
  uint inspect_block_hash[];
};
#endif

uniform uint inspect_first_pixel;
uniform uint inspect_pixel_count;
uniform uint inspect_store_lengths;  // mode 0: also write per-pixel lengths
// 0: no block hashes; 1: write each block's hash (every block visited); 2: visit one block
// in inspect_block_stride, at phase (inspect_block_phase + workgroup) mod stride, and count
// the blocks whose hash differs from the one written before.
uniform uint inspect_block_mode;
uniform uint inspect_block_stride;
uniform uint inspect_block_phase;

#if !LDM_INSPECT_DUMP
// Each invocation's share of the totals, summed per workgroup before any global atomic: one
// atomic per workgroup and total instead of one per pixel (llvmpipe runs an atomic as a loop
// over its SIMD lanes; six per pixel were most of a check's time).
// Shares 0-5 are added to inspect_totals[kShareTotal[i]] (length, pixel visited, unsorted,
// ties, over-long, checksum low word), 6 is xor-ed into the checksum's high word, 7 is the
// block's hash.
const uint kShares = 8u;
const uint kShareTotal[kShares] = uint[](0u, 6u, 1u, 7u, 2u, 3u, 4u, 0u);
shared uint shares[kShares][gl_WorkGroupSize.x];
#endif

uint mix_hash(uint h, uint v) {
  h ^= v;
  h *= 0x01000193u;  // FNV-1a step on 32-bit words
  h ^= h >> 15;
  return h;
}

void main() {
  // No early return: every invocation reaches the barriers below.
  uint block = linear_workgroup_index();
  if (inspect_block_mode == 2u)
    block = block * inspect_block_stride + (inspect_block_phase + block) % inspect_block_stride;
  const uint local = block * gl_WorkGroupSize.x + gl_LocalInvocationID.x;
  const bool in_range = local < inspect_pixel_count;
  const uint pixel = inspect_first_pixel + local;
  uint length = 0u;
#if LDM_INSPECT_DUMP
  uint out_at = in_range ? inspect_data[local] : 0u;
#else
  bool sorted = true;
  float previous = -1.0 / 0.0;
  uint ties = 0u;
  uint hash = 0x811c9dc5u;
#endif
  if (in_range) {
    for (LdmCursor c = ldm_begin(pixel); ldm_valid(c) && length <= LDM_MAX_LIST_LENGTH;
         c = ldm_next(c)) {
      const float depth = ldm_depth(c);
#if LDM_INSPECT_DUMP
      inspect_data[inspect_pixel_count + out_at + length] = floatBitsToUint(depth);
#else
      sorted = sorted && depth >= previous;
      if (length > 0u && depth == previous) ++ties;
      previous = depth;
      hash = mix_hash(hash, floatBitsToUint(depth));
#endif
      ++length;
    }
  }
#if !LDM_INSPECT_DUMP
  const uint me = gl_LocalInvocationID.x;
  if (in_range && inspect_store_lengths != 0u) inspect_data[local] = length;
  const bool listed = in_range && length > 0u;
  shares[0][me] = in_range ? length : 0u;
  shares[1][me] = in_range ? 1u : 0u;
  shares[2][me] = in_range && !sorted ? 1u : 0u;
  shares[3][me] = in_range ? ties : 0u;
  shares[4][me] = in_range && length > LDM_MAX_LIST_LENGTH ? 1u : 0u;
  shares[5][me] = listed ? mix_hash(hash, pixel) : 0u;
  shares[6][me] = listed ? mix_hash(hash * 0x9e3779b9u, pixel + 0x68bc21ebu) : 0u;
  // Position-dependent, so that lists swapped between pixels change the block's hash.
  shares[7][me] = listed ? mix_hash(hash ^ (length * 0x85ebca6bu), pixel) : 0u;
  barrier();
  // Invocation i combines share i of the workgroup (sums wrap as the atomics did; the
  // second checksum word is an xor), then adds it to its total once.
  if (me < kShares) {
    uint combined = 0u;
    for (uint i = 0u; i < gl_WorkGroupSize.x; ++i)
      combined = me == 6u ? combined ^ shares[me][i] : combined + shares[me][i];
    if (me == 7u) {
      if (block * gl_WorkGroupSize.x < inspect_pixel_count) {
        if (inspect_block_mode == 1u) inspect_block_hash[block] = combined;
        if (inspect_block_mode == 2u && inspect_block_hash[block] != combined)
          atomicAdd(inspect_totals[5], 1u);
      }
    } else if (combined != 0u) {
      if (me == 6u) atomicXor(inspect_totals[kShareTotal[me]], combined);
      else atomicAdd(inspect_totals[kShareTotal[me]], combined);
    }
  }
#endif
}
