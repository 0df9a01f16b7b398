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
// keeps the replay's atomics few.
#ifndef LDM_WORK_COUNTERS_GLSL
#define LDM_WORK_COUNTERS_GLSL

#ifdef LDM_WORK_COUNT

layout(std430, binding = WORK_COUNTERS_BINDING) restrict buffer WorkCounters {
  uint work_words[];
};

// A 64-bit total as two words: the carry goes to the high word when the low one wraps.
void work_add_at(uint slot, uint n) {
  if (n == 0u) return;
  const uint before = atomicAdd(work_words[slot], n);
  if (before > 0xFFFFFFFFu - n) atomicAdd(work_words[slot + 1u], 1u);
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

#define work_add(name, n) work_add_at(uint(WORK_##name), uint(n))
#define work_sample(name, value) work_sample_at(uint(WORK_##name), uint(value))
// Code that only counting needs (a local tally): compiled only in the counting variant.
#define WORK_COUNTING 1

#else

#define work_add(name, n)
#define work_sample(name, value)
#define WORK_COUNTING 0

#endif

#endif  // LDM_WORK_COUNTERS_GLSL
