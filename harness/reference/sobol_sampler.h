#pragma once
// Owen-scrambled 2D Sobol points for the reference's per-pixel samples (issue 21: the same
// noise with fewer rays). The first two Sobol dimensions form a (0,2)-sequence: every prefix
// of 2^k points puts one point in each of the 2^k elementary intervals of any shape, so the
// cosine-weighted directions they map to are stratified over the hemisphere at any power of
// two, and the render's doublings (reference_image.h: batches [0, S), [S, 2S), [2S, 4S) ...)
// extend one sequence instead of adding independent points.
//
// Each (seed, pixel) gets its own nested uniform (Owen) scramble, computed with the hash-based
// scramble of Burley, "Practical Hash-based Owen Scrambling" (JCGT 2020): the scramble keeps
// the stratification and makes every point uniformly distributed, so a pixel's mean is an
// unbiased estimate; different seeds give independent scrambles, so the reference's two halves
// (seeds s and s + 1) stay independent and MSE(A, B) / 4 remains the noise of their mean.
#include <cstdint>

#include <glm/glm.hpp>

namespace ldm {

namespace sobol_detail {

inline uint32_t reverse_bits(uint32_t x) {
  x = ((x >> 1) & 0x55555555u) | ((x & 0x55555555u) << 1);
  x = ((x >> 2) & 0x33333333u) | ((x & 0x33333333u) << 2);
  x = ((x >> 4) & 0x0F0F0F0Fu) | ((x & 0x0F0F0F0Fu) << 4);
  x = ((x >> 8) & 0x00FF00FFu) | ((x & 0x00FF00FFu) << 8);
  return (x >> 16) | (x << 16);
}

// A random permutation of [0, 2^32) in which each bit depends only on the bits above it (in
// the bit-reversed order): a nested uniform scramble of the binary digits (Burley 2020, §4).
inline uint32_t laine_karras_permutation(uint32_t x, uint32_t seed) {
  x += seed;
  x ^= x * 0x6c50b47cu;
  x ^= x * 0xb82f1e52u;
  x ^= x * 0xc7afe638u;
  x ^= x * 0x8d22f6e6u;
  return x;
}

inline uint32_t nested_uniform_scramble(uint32_t x, uint32_t seed) {
  return reverse_bits(laine_karras_permutation(reverse_bits(x), seed));
}

// Dimension 0 of Sobol: the van der Corput sequence (the index's bits reversed).
inline uint32_t sobol_dimension0(uint32_t index) { return reverse_bits(index); }

// Dimension 1: primitive polynomial x + 1, direction numbers v_0 = 2^31,
// v_k = v_{k-1} ^ (v_{k-1} >> 1) (the Pascal matrix mod 2).
inline uint32_t sobol_dimension1(uint32_t index) {
  uint32_t result = 0, direction = 0x80000000u;
  for (; index; index >>= 1, direction ^= direction >> 1)
    if (index & 1u) result ^= direction;
  return result;
}

inline uint32_t hash32(uint64_t x) {
  x ^= x >> 33;
  x *= 0xff51afd7ed558ccdull;
  x ^= x >> 33;
  x *= 0xc4ceb9fe1a85ec53ull;
  x ^= x >> 33;
  return uint32_t(x);
}

inline float to_unit_float(uint32_t bits) {
  // The top 24 bits: exactly representable, in [0, 1).
  return float(bits >> 8) * (1.0f / 16777216.0f);
}

}  // namespace sobol_detail

class ScrambledSobol2D {
 public:
  ScrambledSobol2D(uint64_t seed, uint64_t pixel_index) {
    using sobol_detail::hash32;
    const uint64_t key = seed * 0x9e3779b97f4a7c15ull ^ (pixel_index + 0x632be59bd9b4e019ull);
    index_seed_ = hash32(key);
    seed_x_ = hash32(key ^ 0xa0761d6478bd642full);
    seed_y_ = hash32(key ^ 0xe7037ed1a0b428dbull);
  }

  // Point `index` of this pixel's sequence, in [0, 1)^2.
  glm::vec2 point(uint32_t index) const {
    using namespace sobol_detail;
    // Shuffling the index as well (Burley §5) decorrelates pixels and keeps every prefix of
    // 2^k points a scrambled (0,2)-net.
    const uint32_t shuffled = nested_uniform_scramble(index, index_seed_);
    return {to_unit_float(nested_uniform_scramble(sobol_dimension0(shuffled), seed_x_)),
            to_unit_float(nested_uniform_scramble(sobol_dimension1(shuffled), seed_y_))};
  }

 private:
  uint32_t index_seed_, seed_x_, seed_y_;
};

}  // namespace ldm
