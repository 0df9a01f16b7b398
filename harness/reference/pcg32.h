#pragma once
// PCG32 (O'Neill 2014, pcg32_random_r with the 64-bit LCG and XSH-RR output) and the seeding of
// one independent stream per (seed, pass, pixel). Every pixel draws from its own stream, so a
// rendered image depends on the seed only, never on how pixels were spread over threads.
#include <cstdint>

namespace ldm {

// SplitMix64's finaliser: a bijective 64-bit mix, used to decorrelate nearby seeds.
constexpr uint64_t mix64(uint64_t z) {
  z += 0x9e3779b97f4a7c15ull;
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
  return z ^ (z >> 31);
}

class Pcg32 {
 public:
  // `sequence` selects one of 2^63 distinct streams, `state_seed` the start within it.
  Pcg32(uint64_t state_seed, uint64_t sequence) : increment_((sequence << 1u) | 1u) {
    next_u32();
    state_ += state_seed;
    next_u32();
  }

  uint32_t next_u32() {
    const uint64_t old = state_;
    state_ = old * 6364136223846793005ull + increment_;
    const auto xorshifted = static_cast<uint32_t>(((old >> 18u) ^ old) >> 27u);
    const auto rotation = static_cast<uint32_t>(old >> 59u);
    return (xorshifted >> rotation) | (xorshifted << ((32u - rotation) & 31u));
  }

  // Uniform in [0, 1): the top 24 bits, so that every value is exactly representable.
  float next_float() { return float(next_u32() >> 8) * 0x1p-24f; }

 private:
  uint64_t state_ = 0;
  uint64_t increment_;
};

// The stream of one pixel in one rendering pass. Both PCG parameters depend on all three
// inputs: streams that share an increment and differ only in start are correlated.
inline Pcg32 pixel_stream(uint64_t seed, uint32_t pass, uint64_t pixel_index) {
  const uint64_t a = mix64(mix64(seed) ^ pixel_index);
  const uint64_t b = mix64(a ^ (uint64_t(pass) * 0xd1b54a32d192ed03ull + 1u));
  return Pcg32(a, b);
}

}  // namespace ldm
