// The counting replay's blended totals of one geometry pass (ldm_impls/common/blended_work_counts.h):
// one target's four channels (first_channel.. of BLEND_CHANNELS) summed over its pixels, one
// column per invocation, into the running sub-pass's counters; the largest pixel value goes
// to blended_largest, where the host checks that every sum was exact (below 2^24).
#include "common/work_counters.glsl"
layout(local_size_x = 64) in;
layout(binding = 0) uniform sampler2D blended_target;
layout(std430, binding = LDM_BLENDED_LARGEST_BINDING) restrict buffer BlendedLargest {
  uint blended_largest;
};
uniform int resolution;
uniform int first_channel;

const uint blended_slots[BLEND_CHANNELS] = uint[](BLEND_SLOTS);

void main() {
  const int x = int(gl_GlobalInvocationID.x);
  if (x >= resolution) return;
  uvec4 lo = uvec4(0u), hi = uvec4(0u), carry;
  vec4 largest = vec4(0.0);
  for (int y = 0; y < resolution; ++y) {
    const vec4 value = texelFetch(blended_target, ivec2(x, y), 0);
    lo = uaddCarry(lo, uvec4(value), carry);
    hi += carry;
    largest = max(largest, value);
  }
  // Clamped below 2^32 so that the conversion is defined; the limit is far below.
  const float column_largest = min(max(max(largest.x, largest.y), max(largest.z, largest.w)), 4.0e9);
  atomicMax(blended_largest, uint(column_largest));
  for (int c = 0; c < 4; ++c) {
    const int channel = first_channel + c;
    if (channel < BLEND_CHANNELS) work_add_words(blended_slots[channel], lo[c], hi[c]);
  }
}
