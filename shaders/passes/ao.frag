// Ambient occlusion with LDMs (thesis §4.4.1, Listings 5 and 6; Eq. 13):
//   AO(x) = 2/N * sum_i V(d_i) * |cos theta_i|                     (AO_NORMALIZED 0)
// or, normalised so that an unoccluded point gives exactly 1 at any N,
//   AO(x) = sum_i V(d_i) * |cos theta_i| / sum_i |cos theta_i|    (AO_NORMALIZED 1)
// over the N LDM views, each sampled once in the hemisphere around the normal: along
// +forward (the next fragment) when the normal faces +forward, else along -forward (the
// previous one). The normal offset of §4.4.2 moves x by n * sin(angle(n, w)) * k LDM pixels.
// The trace variant (LDM_TRACE) is chosen in passes/ldm_trace.glsl.
#include "passes/ldm_trace.glsl"
#include "passes/trace_steps.glsl"
#include "common/work_counters.glsl"

layout(binding = 0) uniform sampler2D gbuffer_position;
layout(binding = 1) uniform sampler2D gbuffer_normal;
uniform float ao_d_max;
uniform float ao_falloff_exponent;
uniform float ao_normal_offset_pixels;
layout(location = 0) out float out_ao;

float visibility(float distance) {
  if (isinf(distance)) return 1.0;
#if AO_ATTENUATED
  return pow(min(distance / ao_d_max, 1.0), ao_falloff_exponent);  // ambient obscurance
#else
  return 0.0;
#endif
}

// x: the surface point; returns (V * |cos theta|, |cos theta|).
vec2 ao_contribution(uint view_index, vec3 x, vec3 n) {
  const LdmView view = ldm_views[view_index];
  const float cos_theta = dot(view.forward.xyz, n);
  const float sin_alpha = sqrt(max(0.0, 1.0 - cos_theta * cos_theta));
  const vec3 offset_x = x + n * (sin_alpha * ao_normal_offset_pixels * view.eye.w);
  const LdmNeighbours hits = ldm_neighbours(view_index, offset_x, x, n);
  const float weight = abs(cos_theta);
  return vec2(visibility(cos_theta > 0.0 ? hits.ahead : hits.behind) * weight, weight);
}

// One value per direction traced, tallied and added once per pixel (work_counters.glsl).
WORK_SAMPLE_TALLY(ao_entries_read)
WORK_SAMPLE_TALLY(ao_trace_steps)

void main() {
  const ivec2 pixel = ivec2(gl_FragCoord.xy);
  const vec4 position = texelFetch(gbuffer_position, pixel, 0);
  if (position.w == 0.0) {  // background
    out_ao = 0.0;
    return;
  }
  const vec3 n = texelFetch(gbuffer_normal, pixel, 0).xyz;
  work_add(covered_pixels, 1);
  vec2 sum = vec2(0.0);
  for (uint v = 0u; v < LDM_VIEW_COUNT; ++v) {
    const uint before = trace_steps_so_far();
    const uint entries_before = ldm_walk_steps;
    sum += ao_contribution(v, position.xyz, n);
    trace_steps_max(v, trace_steps_so_far() - before);
    work_sample_tally(ao_entries_read, entries_read, ldm_walk_steps - entries_before);
    work_sample_tally(ao_trace_steps, trace_steps, trace_steps_so_far() - before);
  }
  trace_steps_max(LDM_VIEW_COUNT, trace_steps_so_far() + LDM_VIEW_COUNT);
  work_sample_flush(entries_read, ao_entries_read);
  work_sample_flush(trace_steps, ao_trace_steps);
  ldm_work_flush();
#if AO_NORMALIZED
  out_ao = sum.y > 0.0 ? sum.x / sum.y : 1.0;
#else
  out_ao = 2.0 / float(LDM_VIEW_COUNT) * sum.x;
#endif
}
