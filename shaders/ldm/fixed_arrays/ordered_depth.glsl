// An order-preserving map between float depths and uints, for structures that sort depths
// with integer atomics (PSPPFLA's atomicMin, the HA-buffer's 64-bit atomicMax keys).
// floatBitsToUint alone preserves order only for +0.0 and positive floats: -0.0 (which
// interpolation can produce at the near plane) would sort after every positive depth. Setting
// the sign bit of non-negative floats and inverting negative ones orders all non-NaN floats,
// -0.0 just before +0.0, and is exactly invertible, so the stored float is bit-exact.
// Only a NaN maps to 0xFFFFFFFF, which the structures use as their empty value.
#ifndef ORDERED_DEPTH_GLSL
#define ORDERED_DEPTH_GLSL

uint ordered_depth_bits(float depth) {
  const uint bits = floatBitsToUint(depth);
  return (bits & 0x80000000u) != 0u ? ~bits : bits | 0x80000000u;
}

float depth_from_ordered_bits(uint ordered) {
  return uintBitsToFloat((ordered & 0x80000000u) != 0u ? ordered & 0x7FFFFFFFu : ~ordered);
}

#endif
