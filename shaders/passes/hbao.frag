// Horizon-based ambient occlusion (Bavoil, Sainz and Dimitrov 2008; thesis §4.2.3, Eq. 11,
// Listing 15) from the camera's position/normal G-buffer:
//   AO(x) = 1 - 1/N * sum_phi sum_steps W(r) * (sin(h_new) - sin(h_old))
// For each of HBAO_DIRECTIONS screen directions phi, HBAO_STEPS samples march out to the
// radius R (scene units, projected to pixels at x's depth). The horizon starts at the tangent
// angle t (the surface's elevation above the view plane in the slice, from the
// G-buffer's position differences as in Listing 15)
// plus the angle bias (added to the angle itself); a sample above the current horizon and within R raises it and adds
// its rise in sin, weighted by W(r) = 1 - (r/R)^e (HBAO_ATTENUATED 1: the LDM AO's
// V = min(d/d_max, 1)^e as 1 - V, e = 2 the 1 - r^2/R^2 of Bavoil et al.) or 1
// (HBAO_ATTENUATED 0). Elevations are measured from the view
// plane, as in the thesis (eye-space z over the length of eye-space xy).
#include "common/work_counters.glsl"
layout(binding = 0) uniform sampler2D gbuffer_position;
layout(binding = 1) uniform sampler2D gbuffer_normal;
uniform vec3 camera_eye;
uniform vec3 camera_forward;
uniform float focal_pixels;  // (height / 2) / tan(fov_y / 2)
uniform float hbao_radius;   // R = d_max, scene units
uniform float hbao_falloff_exponent;  // e of W = 1 - (r/R)^e
uniform float hbao_angle_bias;  // radians
// A tiled 4x4 random table (the "random texture"): per pixel, a rotation of the direction
// set (radians) and a step offset in (0, 1]. Without jitter every entry is (0, 1).
uniform vec2 hbao_jitter[16];
layout(location = 0) out float out_ao;

const float kPi = 3.14159265358979;

// Elevation of a world-space vector above the view plane, as a tangent.
float tan_elevation(vec3 v) {
  const float toward_camera = -dot(v, camera_forward);
  const float lateral = length(v + toward_camera * camera_forward);
  return toward_camera / max(lateral, 1e-30);
}

// The change of position one pixel along `axis`: the smaller of the forward and backward
// differences (the one on x's own surface at an edge), from a covered neighbour.
vec3 smaller_difference(vec3 x, ivec2 pixel, ivec2 axis) {
  const ivec2 last = textureSize(gbuffer_position, 0) - 1;
  const vec4 ahead = texelFetch(gbuffer_position, min(pixel + axis, last), 0);
  const vec4 behind = texelFetch(gbuffer_position, max(pixel - axis, ivec2(0)), 0);
  const bool has_ahead = ahead.w != 0.0 && pixel + axis == min(pixel + axis, last);
  const bool has_behind = behind.w != 0.0 && pixel - axis == max(pixel - axis, ivec2(0));
  const vec3 forward_difference = ahead.xyz - x, backward_difference = x - behind.xyz;
  if (has_ahead && has_behind)
    return dot(forward_difference, forward_difference) <
                   dot(backward_difference, backward_difference)
               ? forward_difference
               : backward_difference;
  return has_ahead ? forward_difference : has_behind ? backward_difference : vec3(0.0);
}

float tan_to_sin(float t) { return t * inversesqrt(t * t + 1.0); }

void main() {
  const ivec2 pixel = ivec2(gl_FragCoord.xy);
  const vec4 position = texelFetch(gbuffer_position, pixel, 0);
  work_add(fragments, 1);
  if (position.w == 0.0) {  // background
    out_ao = 0.0;
    return;
  }
  work_add(covered_pixels, 1);
#if WORK_COUNTING
  // Directions marched (not skipped for a tangent above the horizon), samples read and
  // horizon rises, summed over the pixel's directions.
  uint work_directions = 0u, work_samples = 0u, work_rises = 0u;
#endif
  const vec3 x = position.xyz;
  const float view_depth = dot(x - camera_eye, camera_forward);
  const float radius_pixels = hbao_radius * focal_pixels / view_depth;
  const float step_pixels = radius_pixels / float(HBAO_STEPS);
  const vec2 jitter = hbao_jitter[(pixel.y & 3) * 4 + (pixel.x & 3)];
  const float radius_squared = hbao_radius * hbao_radius;
  const vec2 size = vec2(textureSize(gbuffer_position, 0));

  const vec3 n = texelFetch(gbuffer_normal, pixel, 0).xyz;
  const float sin_bias = sin(hbao_angle_bias);
  const vec3 dp_du = smaller_difference(x, pixel, ivec2(1, 0));
  const vec3 dp_dv = smaller_difference(x, pixel, ivec2(0, 1));
  float occlusion = 0.0;
  for (int i = 0; i < HBAO_DIRECTIONS; ++i) {
    const float phi = 2.0 * kPi * float(i) / float(HBAO_DIRECTIONS) + jitter.x;
    const vec2 direction = vec2(cos(phi), sin(phi));
    // The surface's tangent in this slice, as in Listing 15: the G-buffer's position
    // derivatives along the screen direction. A straight screen line over a plane is a
    // straight world line, so on a plane every sample lies exactly along this tangent.
    const float tan_tangent = tan_elevation(direction.x * dp_du + direction.y * dp_dv);
    // The bias is added to the angle (Listing 15 adds tan(bias) to its tangent, which
    // vanishes in angle where the surface is seen at a grazing angle).
    const float horizon_angle = atan(tan_tangent) + hbao_angle_bias;
    if (horizon_angle >= 0.5 * kPi) continue;  // nothing in this slice rises above it
    float tan_horizon = tan(horizon_angle);
    float sin_horizon = sin(horizon_angle);
#if WORK_COUNTING
    ++work_directions;
#endif
    for (int j = 0; j < HBAO_STEPS; ++j) {
      const vec2 sample_pixel = gl_FragCoord.xy + direction * (step_pixels * (float(j) + jitter.y));
      if (any(lessThan(sample_pixel, vec2(0.0))) || any(greaterThanEqual(sample_pixel, size)))
        break;  // off screen: the depth buffer knows nothing there
#if WORK_COUNTING
      ++work_samples;
#endif
      const vec4 sample_position = texelFetch(gbuffer_position, ivec2(sample_pixel), 0);
      if (sample_position.w == 0.0) continue;  // background occludes nothing
      const vec3 ray = sample_position.xyz - x;
      const float r_squared = dot(ray, ray);
      if (r_squared == 0.0 || r_squared > radius_squared) continue;
      const float tan_sample = tan_elevation(ray);
      if (tan_sample <= tan_horizon) continue;
      // Samples are read at pixel centres, a little off the slice's line, where the tangent
      // of x's plane differs (much so at grazing angles): a sample must also rise the bias
      // above x's tangent plane itself, so that x's own surface never occludes.
      if (dot(ray, n) <= sin_bias * sqrt(r_squared)) continue;
      const float sin_sample = tan_to_sin(tan_sample);
#if HBAO_ATTENUATED
      const float falloff = hbao_falloff_exponent == 2.0
                                ? 1.0 - r_squared / radius_squared
                                : 1.0 - pow(sqrt(r_squared / radius_squared), hbao_falloff_exponent);
#else
      const float falloff = 1.0;
#endif
      occlusion += (sin_sample - sin_horizon) * falloff;
#if WORK_COUNTING
      ++work_rises;
#endif
      tan_horizon = tan_sample;
      sin_horizon = sin_sample;
    }
  }
  work_add(directions, work_directions);
  work_add(samples, work_samples);
  work_add(horizon_rises, work_rises);
  work_sample(steps, work_samples);
  out_ao = 1.0 - occlusion / float(HBAO_DIRECTIONS);
}
