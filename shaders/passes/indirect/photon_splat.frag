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

void main() {
  const ivec2 pixel = ivec2(gl_FragCoord.xy);
#if WORK_COUNTING
  if (!gl_HelperInvocation) work_add(fragments, 1);
#endif
  const vec4 x = texelFetch(camera_position, pixel, 0);
  if (x.w == 0.0) discard;
  const float l = length(splat_to_filter * (x.xyz - splat_position));
  if (!(l < 1.0)) discard;
#if WORK_COUNTING
  if (!gl_HelperInvocation) work_add(fragments_in_kernel, 1);
#endif
  const float q = 1.0 - l * l;
  const float kernel = 3.0 / 3.14159265358979 * q * q;
  const vec3 rho = texelFetch(camera_albedo, pixel, 0).rgb;
  out_radiance = vec4(rho * splat_irradiance * kernel, 0.0);
}
