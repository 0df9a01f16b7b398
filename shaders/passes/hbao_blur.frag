// One direction of HBAO's separable cross-bilateral blur (harness/passes/hbao_kernel.h): the
// AO of pixel p becomes the weighted mean of the AO at p + k * blur_step, |k| <= radius, with
//   w(k) = exp(-k^2 / (2 sigma^2)) * exp(-(plane_distance / footprint)^2),
// sigma = radius / 2, plane_distance the distance of the tap's G-buffer point from p's tangent
// plane (normal n) and footprint the size of one pixel at p's depth. Taps on p's own surface
// weigh by distance alone; taps on another surface (a depth edge, the other wall of a corner)
// weigh ~0, so occlusion does not bleed across them. Background taps are skipped, and a
// background pixel stays 0.
#include "common/work_counters.glsl"
layout(binding = 0) uniform sampler2D gbuffer_position;
layout(binding = 1) uniform sampler2D gbuffer_normal;
layout(binding = 2) uniform sampler2D blur_source;
uniform vec3 camera_eye;
uniform vec3 camera_forward;
uniform float focal_pixels;
uniform ivec2 blur_step;  // (1, 0) or (0, 1)
layout(location = 0) out float out_ao;

void main() {
  const ivec2 pixel = ivec2(gl_FragCoord.xy);
  const vec4 position = texelFetch(gbuffer_position, pixel, 0);
  work_add(fragments, 1);
  if (position.w == 0.0) {
    out_ao = 0.0;
    return;
  }
#if WORK_COUNTING
  uint work_taps = 0u;  // taps weighed (inside the image, over a surface)
#endif
  const vec3 x = position.xyz;
  const vec3 n = texelFetch(gbuffer_normal, pixel, 0).xyz;
  const float footprint = dot(x - camera_eye, camera_forward) / focal_pixels;
  const float sigma = max(0.5 * float(HBAO_BLUR_RADIUS), 0.5);
  const ivec2 last = textureSize(gbuffer_position, 0) - 1;
  float sum = texelFetch(blur_source, pixel, 0).r, weights = 1.0;
  for (int k = -HBAO_BLUR_RADIUS; k <= HBAO_BLUR_RADIUS; ++k) {
    if (k == 0) continue;
    const ivec2 tap = pixel + k * blur_step;
    if (any(lessThan(tap, ivec2(0))) || any(greaterThan(tap, last))) continue;
    const vec4 tap_position = texelFetch(gbuffer_position, tap, 0);
    if (tap_position.w == 0.0) continue;
    const float plane_distance = abs(dot(tap_position.xyz - x, n)) / footprint;
    const float w = exp(-float(k * k) / (2.0 * sigma * sigma) - plane_distance * plane_distance);
    sum += w * texelFetch(blur_source, tap, 0).r;
    weights += w;
#if WORK_COUNTING
    ++work_taps;
#endif
  }
  work_add(taps, work_taps);
  out_ao = sum / weights;
}
