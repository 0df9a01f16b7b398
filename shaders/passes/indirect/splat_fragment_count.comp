// The counting replay's splat fragments (photon_splat.frag under LDM_WORK_COUNT blends 1 per
// fragment into x and 1 per fragment inside the kernel into y of a 32-bit float target):
// summed here, one column of pixels per invocation, into the splatting sub-pass's
// `fragments` and `fragments_in_kernel`. A pixel's count is an exact float integer up to
// 2^24, which the pass guarantees: a pixel gets at most one fragment per splat, and with more
// photons than that it counts with atomics instead (photon_splat.frag).
#include "common/work_counters.glsl"
layout(local_size_x = 64) in;
layout(binding = 0) uniform sampler2D splat_counts;
uniform int width;
uniform int height;

void main() {
  const int x = int(gl_GlobalInvocationID.x);
  if (x >= width) return;
  uint fragments_lo = 0u, fragments_hi = 0u, in_kernel_lo = 0u, in_kernel_hi = 0u, carry;
  for (int y = 0; y < height; ++y) {
    const vec2 count = texelFetch(splat_counts, ivec2(x, y), 0).xy;
    fragments_lo = uaddCarry(fragments_lo, uint(count.x), carry);
    fragments_hi += carry;
    in_kernel_lo = uaddCarry(in_kernel_lo, uint(count.y), carry);
    in_kernel_hi += carry;
  }
  work_add_words(uint(WORK_fragments), fragments_lo, fragments_hi);
  work_add_words(uint(WORK_fragments_in_kernel), in_kernel_lo, in_kernel_hi);
}
