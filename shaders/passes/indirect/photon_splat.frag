// Photon splatting, fragment stage: the radiance estimate of Eq. 27 for this pixel's surface
// point x (camera G-buffer), L = f_r * E_p * pi * K(|M (x - x_p)|) with the Lambertian
// f_r = rho / pi and Silverman's second-order kernel normalised over the unit disc,
// K(l) = 3/pi (1 - l^2)^2 (the thesis prints pi/3; only 3/pi integrates to 1), summed by
// additive blending.
#include "common/work_counters.glsl"
layout(binding = 0) uniform sampler2D camera_position;
layout(binding = 1) uniform sampler2D camera_albedo;

flat in vec3 splat_position;
flat in vec3 splat_irradiance;
flat in mat3 splat_to_filter;
layout(location = 0) out vec4 out_radiance;
#if WORK_COUNTING && !SPLAT_COUNT_BY_ATOMICS
// The counting replay counts this stage's fragments by blending, not by atomics (two per
// fragment made the counted splat several times the measured one): each fragment adds 1 to
// x, and 1 to y when it is inside the kernel, of a 32-bit float target that
// splat_fragment_count.comp then sums (helpers write nothing, so they are left out as the
// counters declare). A fragment that the measured shader discards adds zero radiance
// instead, which leaves every sum bit for bit as it was (x + 0 = x for the non-negative sums).
// Where a pixel's count could pass 2^24 (more splats than that), floats would not hold it:
// the pass compiles the variant with SPLAT_COUNT_BY_ATOMICS, one atomic per fragment.
layout(location = 1) out vec2 out_splat_count;
#define SPLAT_REJECT { out_radiance = vec4(0.0); return; }
#else
#define SPLAT_REJECT discard
#endif

void main() {
  const ivec2 pixel = ivec2(gl_FragCoord.xy);
#if WORK_COUNTING && SPLAT_COUNT_BY_ATOMICS
  if (!gl_HelperInvocation) work_add(fragments, 1);
#elif WORK_COUNTING
  out_splat_count = vec2(1.0, 0.0);
#endif
  const vec4 x = texelFetch(camera_position, pixel, 0);
  if (x.w == 0.0) SPLAT_REJECT;
  const float l = length(splat_to_filter * (x.xyz - splat_position));
  if (!(l < 1.0)) SPLAT_REJECT;
#if WORK_COUNTING && SPLAT_COUNT_BY_ATOMICS
  if (!gl_HelperInvocation) work_add(fragments_in_kernel, 1);
#elif WORK_COUNTING
  out_splat_count.y = 1.0;
#endif
  const float q = 1.0 - l * l;
  const float kernel = 3.0 / 3.14159265358979 * q * q;
  const vec3 rho = texelFetch(camera_albedo, pixel, 0).rgb;
  out_radiance = vec4(rho * splat_irradiance * kernel, 0.0);
}
