// HA-buffer keys and hash function (thesis §3.2.13; Lefebvre, Hornus and Lasram 2013),
// shared by construction and query. With HA_KEY_BITS 64 the including shader must first
// enable GL_ARB_gpu_shader_int64 (the #extension lines must precede any declaration).
//
// A key packs, from the most significant bits down, the entry's age + 1 (8 bits; 0 is the
// empty entry) and its depth INVERTED. One atomicMax then compares age first (Robin Hood:
// the older entry keeps the slot) and, at equal age, keeps the NEARER fragment. Two entries
// of equal age at one slot belong to one pixel (age equivalence), so a pixel's entries come
// out in ascending depth as its age increases: the table needs no sort pass (§3.2.13).
//   HA_KEY_BITS 32: [age+1 : 8][0xFFFFFF - q : 24], q = round(depth / step) with the step
//                   2^HA_DEPTH_STEP_LOG2, the smallest power of two >= depth_range/(2^24-1).
//                   A power of two makes quantising and decoding exact in float, so the
//                   decoded depth differs from the rasterised one by at most step / 2.
//   HA_KEY_BITS 64: [age+1 : 8][~ordered depth bits : 32][0 : 24], the float itself,
//                   bit-exact; the low 24 bits are left for a payload.
#ifndef HA_KEYS_GLSL
#define HA_KEYS_GLSL

#include "ldm/fixed_arrays/ordered_depth.glsl"

#if HA_KEY_BITS == 64
#define HaKey uint64_t
const uint HA_AGE_SHIFT = 56u;
const HaKey HA_EMPTY_KEY = 0ul;
const HaKey HA_DEPTH_MASK = 0x00FFFFFFFFFFFFFFul;  // every bit below the age

HaKey ha_depth_bits(float depth) { return uint64_t(~ordered_depth_bits(depth)) << 24u; }
float ha_key_depth(HaKey key) { return depth_from_ordered_bits(~uint(key >> 24u)); }
#else
#define HaKey uint
const uint HA_AGE_SHIFT = 24u;
const HaKey HA_EMPTY_KEY = 0u;
const HaKey HA_DEPTH_MASK = 0x00FFFFFFu;

HaKey ha_depth_bits(float depth) {
  // Depths lie in [0, depth_range]; the clamps only guard interpolation at the planes.
  const float q = min(round(ldexp(max(depth, 0.0), -(HA_DEPTH_STEP_LOG2))), 16777215.0);
  return HA_DEPTH_MASK - uint(q);
}
float ha_key_depth(HaKey key) {
  return ldexp(float(HA_DEPTH_MASK - (key & HA_DEPTH_MASK)), (HA_DEPTH_STEP_LOG2));
}
#endif

HaKey ha_key(uint age, HaKey depth_bits) { return (HaKey(age + 1u) << HA_AGE_SHIFT) | depth_bits; }
HaKey ha_key_aged(HaKey key, uint age) { return ha_key(age, key & HA_DEPTH_MASK); }
// The key's age; 0xFFFFFFFF for the empty key, which matches no age.
uint ha_key_age(HaKey key) { return uint(key >> HA_AGE_SHIFT) - 1u; }

// o_a, a = 0 .. HA_MAX_AGE: fixed pseudo-random offsets in [0, |H|) made on the host.
layout(std430, binding = LDM_STRUCTURE_BINDING1) readonly restrict buffer HaOffsets {
  uint ha_offsets[];
};

// h(p, a) = (p + o_a) mod |H|. p and o_a are below |H| < 2^31, so the sum cannot wrap.
uint ha_slot(uint pixel, uint age) {
  const uint sum = pixel + ha_offsets[age];
  return sum >= HA_TABLE_SIZE ? sum - HA_TABLE_SIZE : sum;
}

// Age equivalence: the pixel whose age-`age` entry lives in `slot`, p = (h - o_a) mod |H|.
// Unique because |H| >= N * R_LDM^2, the number of pixels.
uint ha_pixel_of(uint slot, uint age) {
  const uint offset = ha_offsets[age];
  return slot >= offset ? slot - offset : slot + (HA_TABLE_SIZE - offset);
}

#endif
