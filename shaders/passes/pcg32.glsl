// PCG32 as harness/reference/pcg32.h has it (O'Neill 2014: 64-bit LCG, XSH-RR output) and its
// per-pixel streams, in GL 4.5 core GLSL: 64-bit integers as uvec2 (x low, y high word), so
// that a shader draws exactly the numbers the CPU's Pcg32 draws for the same seed, pass and
// pixel (the CPU RTAO's samples, when given the same seed).
//
// pixel_stream(seed, pass, pixel) = Pcg32(a, b) with a = mix64(mix64(seed) ^ pixel) and
// b = mix64(a ^ (pass * 0xd1b54a32d192ed03 + 1)); the two pixel-independent parts,
// mix64(seed) and pass * 0xd1b54a32d192ed03 + 1, come from the CPU as uniforms.

uvec2 add64(uvec2 a, uvec2 b) {
  uint carry;
  const uint low = uaddCarry(a.x, b.x, carry);
  return uvec2(low, a.y + b.y + carry);
}

// The low 64 bits of a * b.
uvec2 mul64(uvec2 a, uvec2 b) {
  uint high, low;
  umulExtended(a.x, b.x, high, low);
  return uvec2(low, high + a.x * b.y + a.y * b.x);
}

uvec2 shr64(uvec2 a, uint n) {  // 0 < n < 64
  if (n >= 32u) return uvec2(a.y >> (n - 32u), 0u);
  return uvec2((a.x >> n) | (a.y << (32u - n)), a.y >> n);
}

uvec2 shl1_or1(uvec2 a) { return uvec2((a.x << 1) | 1u, (a.y << 1) | (a.x >> 31)); }

// SplitMix64's finaliser.
uvec2 mix64(uvec2 z) {
  z = add64(z, uvec2(0x7f4a7c15u, 0x9e3779b9u));
  z = mul64(z ^ shr64(z, 30u), uvec2(0x1ce4e5b9u, 0xbf58476du));
  z = mul64(z ^ shr64(z, 27u), uvec2(0x133111ebu, 0x94d049bbu));
  return z ^ shr64(z, 31u);
}

struct Pcg32 {
  uvec2 state, increment;
};

uint pcg32_next(inout Pcg32 rng) {
  const uvec2 old = rng.state;
  rng.state = add64(mul64(old, uvec2(0x4c957f2du, 0x5851f42du)), rng.increment);
  const uint xorshifted = shr64(shr64(old, 18u) ^ old, 27u).x;
  const uint rotation = old.y >> 27;  // old >> 59
  return (xorshifted >> rotation) | (xorshifted << ((32u - rotation) & 31u));
}

// Uniform in [0, 1): the top 24 bits, as Pcg32::next_float.
float pcg32_next_float(inout Pcg32 rng) { return float(pcg32_next(rng) >> 8) * (1.0 / 16777216.0); }

Pcg32 pcg32_seeded(uvec2 state_seed, uvec2 sequence) {
  Pcg32 rng;
  rng.state = uvec2(0u);
  rng.increment = shl1_or1(sequence);
  pcg32_next(rng);
  rng.state = add64(rng.state, state_seed);
  pcg32_next(rng);
  return rng;
}

Pcg32 pixel_stream(uvec2 seed_mixed, uvec2 pass_term, uint pixel_index) {
  const uvec2 a = mix64(seed_mixed ^ uvec2(pixel_index, 0u));
  const uvec2 b = mix64(a ^ pass_term);
  return pcg32_seeded(a, b);
}
