// Photon tracing through the LDM (thesis §5.4.1): one invocation per light texel.
//  1. a primary photon per texel inside the spot's cone that hits a surface in the light's
//     G-buffer, carrying the flux I(d) * (solid angle of the texel) and its differential,
//     transferred to the hit x1;
//  2. split into one secondary photon per LDM view direction (+forward and -forward) that
//     lies in x1's hemisphere, each carrying rho1 * Phi1 * w: the emission `thesis`
//     (EMISSION_NORMALIZED 0) weighs w = |cos| * 2 / N, rho/pi * |cos| times the solid angle
//     2 pi / N each of the 2N directions stands for (the EQ partition, docs/design/departures.md),
//     whose sum over the hemisphere's N directions is rho1 * Phi1 only on average over
//     orientations (a quadrature, as AO's Eq. 13); `normalized` (EMISSION_NORMALIZED 1)
//     weighs w = |cos| / (sum of |cos| over the N directions): exactly rho1 * Phi1 in all;
//  3. each traced with the AO trace (passes/ldm_trace.glsl, the same variants), reflected
//     (quaternion rotation of its directional differential), transferred to the hit x2,
//     depth-tested against the camera's G-buffer, footprint-culled and appended.
// With PHOTON_CAPACITY 0 (a uniform) nothing is written: the counters alone (sizing census).
// Every texel's flux is tallied by its fate (photon.glsl's PHOTON_TALLY_*): the flux audit.
#include "passes/ldm_trace.glsl"
#include "passes/trace_steps.glsl"
#include "common/spot_light.glsl"
#include "passes/indirect/photon.glsl"
#include "passes/indirect/photon_differential.glsl"
#include "common/work_counters.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(binding = 0) uniform sampler2D light_position;  // xyz, w = 1 where a surface was hit
layout(binding = 1) uniform sampler2D light_normal;    // faces the light
layout(binding = 2) uniform sampler2D light_albedo;
layout(binding = 3) uniform sampler2D camera_position;  // camera G-buffer, w = 0: background
layout(binding = 4) uniform sampler2D camera_normal;

#include "passes/indirect/photon_visibility.glsl"

layout(std430, binding = INDIRECT_PHOTONS_BINDING) writeonly restrict buffer Photons {
  Photon photons[];
};
layout(std430, binding = INDIRECT_COUNTERS_BINDING) restrict buffer PhotonCounters {
  uint photon_counters[];
};
// Per light texel: PHOTON_TALLY_ENTRIES entries (photon.glsl), the flux by its fate.
layout(std430, binding = INDIRECT_TALLY_BINDING) writeonly restrict buffer PhotonTally {
  vec4 photon_tally[];
};

uniform uint photon_capacity;
uniform int light_resolution;
uniform vec3 light_forward, light_right, light_up;  // unit axes of the light's image plane
uniform float light_tan_half;                        // tan(outer angle)
uniform float footprint_threshold;  // max norm of s * D x, scene units
uniform float splat_scale;          // s
uniform float normal_offset_pixels;
uniform int emission_normalized;    // 0: thesis (|cos| 2 / N), 1: normalized

uint counts[PHOTON_COUNTERS];
#if WORK_COUNTING
uint work_stored = 0u;  // photons this invocation wrote into the buffer
#endif

// Traces one secondary photon and returns its fate (a PHOTON_TALLY_* index).
uint emit_secondary(uint texel_index, uint view, bool ahead, vec3 x1, vec3 n1, vec3 d1,
                    PhotonDifferential primary, vec3 flux) {
  const LdmView v = ldm_views[view];
  const vec3 w_o = ahead ? v.forward.xyz : -v.forward.xyz;
  // The normal offset of §4.4.2, as the AO pass applies it.
  const float cos_theta = dot(v.forward.xyz, n1);
  const float sin_alpha = sqrt(max(0.0, 1.0 - cos_theta * cos_theta));
  const vec3 offset_x = x1 + n1 * (sin_alpha * normal_offset_pixels * v.eye.w);
  const LdmNeighbours hits = ldm_neighbours(view, offset_x, x1, n1);
  const float t = ahead ? hits.ahead : hits.behind;
  if (isinf(t)) {
    ++counts[PHOTON_COUNT_ESCAPED];
    return PHOTON_TALLY_ESCAPED;
  }
  vec3 x2 = offset_x + t * w_o;
  vec3 n2;
  const uint seen = camera_sees(x2, w_o, n2);
  if (seen != PHOTON_SEEN) {
    ++counts[PHOTON_COUNT_CULLED_DEPTH];
    if (seen == PHOTON_TALLY_CULLED_OUTSIDE) ++counts[PHOTON_COUNT_CULLED_OUTSIDE];
    if (seen == PHOTON_TALLY_CULLED_BACKSIDE) ++counts[PHOTON_COUNT_CULLED_BACKSIDE];
    return seen;
  }
  PhotonDifferential p = primary;
  if (!photon_diffuse_reflect(p, -d1, w_o) || !photon_transfer(p, w_o, n2, distance(x1, x2)) ||
      !(photon_footprint_area(p) > 0.0)) {
    ++counts[PHOTON_COUNT_DEGENERATE];
    return PHOTON_TALLY_DEGENERATE;
  }
  const vec3 extent = max(abs(p.du_x), abs(p.dv_x)) * splat_scale;
  if (max(max(extent.x, extent.y), extent.z) > footprint_threshold) {
    ++counts[PHOTON_COUNT_CULLED_FOOTPRINT];
    return PHOTON_TALLY_CULLED_FOOTPRINT;
  }
  ++counts[PHOTON_COUNT_APPENDS];
  const uint id = atomicAdd(photon_counters[PHOTON_COUNT_APPENDS], 1u);
  if (id >= photon_capacity) return PHOTON_TALLY_OVERFLOW;  // counted by the counter, not stored
#if WORK_COUNTING
  ++work_stored;
#endif
  photons[id].position = vec4(x2, uintBitsToFloat(texel_index));
  photons[id].normal = vec4(n2, uintBitsToFloat(view * 2u + (ahead ? 1u : 0u)));
  photons[id].du = vec4(p.du_x, 0.0);
  photons[id].dv = vec4(p.dv_x, 0.0);
  photons[id].flux = vec4(flux, 0.0);
  return PHOTON_TALLY_STORED;
}

// One value per secondary photon traced, tallied and added once per invocation.
WORK_SAMPLE_TALLY(photon_trace_steps)
WORK_SAMPLE_TALLY(photon_entries_read)

void main() {
  const ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(texel, ivec2(light_resolution)))) return;
  work_add(invocations, 1);
  for (uint i = 0u; i < PHOTON_COUNTERS; ++i) counts[i] = 0u;
  const uint texel_index = uint(texel.y * light_resolution + texel.x);
  vec3 fate[PHOTON_TALLY_ENTRIES];
  for (uint i = 0u; i < PHOTON_TALLY_ENTRIES; ++i) fate[i] = vec3(0.0);
  float emitted_primary = 0.0;

  // The texel centre's direction; the spot's cone is the image's inscribed circle.
  const vec2 ndc = (vec2(texel) + 0.5) / float(light_resolution) * 2.0 - 1.0;
  const vec4 hit = texelFetch(light_position, texel, 0);
  if (dot(ndc, ndc) <= 1.0 && hit.w != 0.0) {
    const vec3 d_hat = light_forward + light_tan_half * (ndc.x * light_right + ndc.y * light_up);
    const float texel_side = 2.0 * light_tan_half / float(light_resolution);
    // Flux through the texel: I(d) times its solid angle, texel area * cos^3 on the plane at 1.
    const float d_len = length(d_hat);
    const vec3 primary_flux =
        spot_radiant_intensity(d_hat) * (texel_side * texel_side / (d_len * d_len * d_len));
    ++counts[PHOTON_COUNT_PRIMARY];
    fate[PHOTON_TALLY_PRIMARY] = primary_flux;
    emitted_primary = 1.0;

    const vec3 d1 = d_hat / d_len;
    const vec3 x1 = hit.xyz;
    const vec3 n1 = texelFetch(light_normal, texel, 0).xyz;
    PhotonDifferential primary =
        photon_at_light(d_hat, texel_side * light_right, texel_side * light_up);
    if (!photon_transfer(primary, d1, n1, distance(spot_position, x1))) {
      ++counts[PHOTON_COUNT_PRIMARY_DEGENERATE];
    } else {
      const vec3 reflected = primary_flux * texelFetch(light_albedo, texel, 0).rgb;  // rho * Phi1
      fate[PHOTON_TALLY_REFLECTED] = reflected;
      // The weights' normaliser: N / 2 (thesis) or the sum of |cos| over the hemisphere's
      // directions (normalized; > 0, since some view axis is not tangent to the surface).
      float normaliser = 0.5 * float(LDM_VIEW_COUNT);
      if (emission_normalized != 0) {
        normaliser = 0.0;
        for (uint view = 0u; view < LDM_VIEW_COUNT; ++view)
          normaliser += abs(dot(ldm_views[view].forward.xyz, n1));
      }
      for (uint view = 0u; view < LDM_VIEW_COUNT; ++view) {
        const float cos_o = dot(ldm_views[view].forward.xyz, n1);
        if (cos_o == 0.0) continue;  // tangent: neither side is in the hemisphere
        const vec3 flux = reflected * (abs(cos_o) / normaliser);
        ++counts[PHOTON_COUNT_EMITTED];
        fate[PHOTON_TALLY_EMITTED] += flux;
        const uint before = trace_steps_so_far();
        const uint entries_before = ldm_walk_steps;
        const uint where = emit_secondary(texel_index, view, cos_o > 0.0, x1, n1, d1, primary, flux);
        fate[where] += flux;
        trace_steps_max(view, trace_steps_so_far() - before);
        work_sample_tally(photon_trace_steps, trace_steps, trace_steps_so_far() - before);
        work_sample_tally(photon_entries_read, entries_read, ldm_walk_steps - entries_before);
      }
      // The view loop's iterations (twice with the normaliser's loop) beside the walks'.
      trace_steps_max(LDM_VIEW_COUNT,
                      trace_steps_so_far() + LDM_VIEW_COUNT * (emission_normalized != 0 ? 2u : 1u));
    }
  }
  const uint base = PHOTON_TALLY_ENTRIES * texel_index;
  for (uint i = 0u; i < PHOTON_TALLY_ENTRIES; ++i)
    photon_tally[base + i] = vec4(fate[i], i == PHOTON_TALLY_PRIMARY ? emitted_primary : 0.0);
  // The append counter is counted as it goes; the rest once per invocation.
  for (uint i = 1u; i < PHOTON_COUNTERS; ++i)
    if (counts[i] != 0u) atomicAdd(photon_counters[i], counts[i]);
  work_add(photons_primary, counts[PHOTON_COUNT_PRIMARY]);
  work_add(photons_traced, counts[PHOTON_COUNT_EMITTED]);
  work_add(photons_appended, counts[PHOTON_COUNT_APPENDS]);
  work_add(photons_stored, work_stored);
  work_sample_flush(trace_steps, photon_trace_steps);
  work_sample_flush(entries_read, photon_entries_read);
  ldm_work_flush();
}
