// What a shader did, counted in the untimed counting replay (harness/measure/work_counters.h).
//
//   work_add(name, n)        adds n to the total `name` of the running sub-pass
//   work_sample(name, v)     adds one value v to the distribution `name` (one per query:
//                            a ray's trace steps, a list's nodes visited)
//
// `name` is the counter's name as its owner declares it (WorkCounter::name); the harness
// passes its slot as WORK_<name>, the same in each sub-pass's block of the buffer, and binds
// the running sub-pass's block. A name nobody declared fails to compile in the counting
// variant. Without LDM_WORK_COUNT (every timed program) both are empty macros: their
// arguments are not even evaluated, so the measured code is the code without counting.
//
// Counting in a hot loop: sum into a local variable and add it once per invocation, which
// keeps the replay's atomics few (the tallies below, where the loop is someone else's).
#ifndef LDM_WORK_COUNTERS_GLSL
#define LDM_WORK_COUNTERS_GLSL

#ifdef LDM_WORK_COUNT

layout(std430, binding = WORK_COUNTERS_BINDING) restrict buffer WorkCounters {
  uint work_words[];
};

// A 64-bit total as two words: the carry goes to the high word when the low one wraps.
void work_add_words(uint slot, uint lo, uint hi) {
  const uint before = atomicAdd(work_words[slot], lo);
  const uint carry = before > 0xFFFFFFFFu - lo ? 1u : 0u;
  if (hi + carry != 0u) atomicAdd(work_words[slot + 1u], hi + carry);
}
void work_add_at(uint slot, uint n) {
  if (n == 0u) return;
  work_add_words(slot, n, 0u);
}

uint work_bin(uint value) {
  if (value < uint(WORK_EXACT_BINS)) return value;
  return uint(WORK_EXACT_BINS) + uint(findMSB(value)) - uint(WORK_EXACT_BITS);
}

// The sum (2 words) and max of the large values, then the histogram: a value below
// WORK_EXACT_BINS is counted by its bin alone (one atomic), its share of the count, sum and
// max read back from the exact bins (harness/measure/work_counters.cpp).
void work_sample_at(uint slot, uint value) {
  atomicAdd(work_words[slot + uint(WORK_DISTRIBUTION_HEADER) + work_bin(value)], 1u);
  if (value >= uint(WORK_EXACT_BINS)) {
    work_add_at(slot, value);
    atomicMax(work_words[slot + 2u], value);
  }
}

#define work_sample(name, value) work_sample_at(uint(WORK_##name), uint(value))

#if defined(WORK_BLEND_TARGETS) && !defined(WORK_ATOMICS_ONLY)
// Totals counted by blending (a fragment stage of the LDM geometry pass in the counting
// replay: ldm_impls/common/blended_work_counts.h). Each total the shader adds has a channel
// (WORK_CHANNEL_<name>) of WORK_BLEND_TARGETS 32-bit float targets that the draw blends
// additively; the rasterizer sums them into the sub-pass's counters after the draw. A
// per-fragment atomic costs llvmpipe 15-19 ns per fragment and site (a loop over its SIMD
// lanes); a fragment's outputs cost nothing per site. Distributions keep their atomics.
// WORK_BLEND_BEGIN() zeroes the outputs: it must run before anything adds, in every
// invocation that writes (LDM_SKIP_HELPER_INVOCATIONS, which starts every such main()).
// Other stages of the program define WORK_ATOMICS_ONLY before including this.
layout(location = 0) out vec4 work_blended[WORK_BLEND_TARGETS];
#define WORK_BLEND_BEGIN() \
  for (int work_target = 0; work_target < WORK_BLEND_TARGETS; ++work_target) \
    work_blended[work_target] = vec4(0.0)
#define work_add(name, n) \
  (work_blended[WORK_CHANNEL_##name / 4][WORK_CHANNEL_##name % 4] += float(uint(n)))
#else
#define WORK_BLEND_BEGIN()
#define work_add(name, n) work_add_at(uint(WORK_##name), uint(n))
#endif

// Tallies: counting in a hot loop that has no end of its own (a structure's query, called
// per node a pass visits), summed in a private variable and added once per invocation by
// the code that owns the loop (ldm_work_flush()). Each atomic of the counting replay costs
// about what the work it counts does, so per-node atomics would triple the frame it counts.
//   WORK_TALLY(var)                       a total's tally
//   work_tally(var, n)                    adds n to it
//   work_add_tally(name, var)             adds it to the total `name` and clears it
//   WORK_SAMPLE_TALLY(var)                a distribution's tally: its values 0 to 3 counted,
//                                         and the sum and max of its large values
//   work_sample_tally(var, name, value)   one value (4 to 255: its bin's atomic at once;
//                                         larger: the bin's atomic, the sum and max tallied)
//   work_sample_flush(name, var)          adds the tallied values to `name` and clears it
#define WORK_TALLY(var) uint var = 0u;
#define work_tally(var, n) (var += uint(n))
#define work_add_tally(name, var) (work_add_at(uint(WORK_##name), var), var = 0u)
#define WORK_SAMPLE_TALLY(var) WorkSampleTally var = work_sample_tally_zero();
#define work_sample_tally(var, name, value) work_sample_tally_at(var, uint(WORK_##name), uint(value))
#define work_sample_flush(name, var) (work_sample_flush_at(uint(WORK_##name), var), var = work_sample_tally_zero())

struct WorkSampleTally {
  uvec4 small;          // how many values 0, 1, 2 and 3
  uint sum_lo, sum_hi;  // the sum of the values of WORK_EXACT_BINS or more
  uint large_max;       // and their max
};

WorkSampleTally work_sample_tally_zero() { return WorkSampleTally(uvec4(0u), 0u, 0u, 0u); }

void work_sample_tally_at(inout WorkSampleTally tally, uint slot, uint value) {
  if (value == 0u) tally.small.x += 1u;
  else if (value == 1u) tally.small.y += 1u;
  else if (value == 2u) tally.small.z += 1u;
  else if (value == 3u) tally.small.w += 1u;
  else {
    atomicAdd(work_words[slot + uint(WORK_DISTRIBUTION_HEADER) + work_bin(value)], 1u);
    if (value >= uint(WORK_EXACT_BINS)) {
      uint carry;
      tally.sum_lo = uaddCarry(tally.sum_lo, value, carry);
      tally.sum_hi += carry;
      tally.large_max = max(tally.large_max, value);
    }
  }
}

void work_sample_flush_at(uint slot, WorkSampleTally tally) {
  const uint bins = slot + uint(WORK_DISTRIBUTION_HEADER);  // values below 4 are exact bins
  if (tally.small.x != 0u) atomicAdd(work_words[bins], tally.small.x);
  if (tally.small.y != 0u) atomicAdd(work_words[bins + 1u], tally.small.y);
  if (tally.small.z != 0u) atomicAdd(work_words[bins + 2u], tally.small.z);
  if (tally.small.w != 0u) atomicAdd(work_words[bins + 3u], tally.small.w);
  if (tally.large_max != 0u) {  // the header: the large values' sum (2 words) and max
    work_add_words(slot, tally.sum_lo, tally.sum_hi);
    atomicMax(work_words[slot + 2u], tally.large_max);
  }
}
// Code that only counting needs (a local tally): compiled only in the counting variant.
#define WORK_COUNTING 1

#else

#define work_add(name, n)
#define work_sample(name, value)
#define WORK_BLEND_BEGIN()
#define WORK_TALLY(var)
#define work_tally(var, n)
#define work_add_tally(name, var)
#define WORK_SAMPLE_TALLY(var)
#define work_sample_tally(var, name, value)
#define work_sample_flush(name, var)
#define WORK_COUNTING 0

#endif

#endif  // LDM_WORK_COUNTERS_GLSL
