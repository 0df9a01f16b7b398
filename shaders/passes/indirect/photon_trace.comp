// Photon tracing through the LDM (thesis §5.4.1): one invocation per light texel.
//  1. a primary photon per texel inside the spot's cone that hits a surface in the light's
//     G-buffer, carrying the flux I(d) * (solid angle of the texel) and its differential,
//     transferred to the hit x1;
//  2. split into one secondary photon per LDM view direction (+forward and -forward) that
//     lies in x1's hemisphere, each carrying Phi1 * rho1/pi * |cos| * (2 pi / N), the solid
//     angle each of the 2N directions stands for (the EQ partition, docs/design/departures.md);
//  3. each traced with the AO trace (passes/ldm_trace.glsl, the same variants), reflected
//     (quaternion rotation of its directional differential), transferred to the hit x2,
//     depth-tested against the camera's G-buffer, footprint-culled and appended.
// With PHOTON_CAPACITY 0 (a uniform) nothing is written: the counters alone (sizing census).
#include "passes/ldm_trace.glsl"
#include "passes/trace_steps.glsl"
#include "common/spot_light.glsl"
#include "passes/indirect/photon.glsl"
#include "passes/indirect/photon_differential.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(binding = 0) uniform sampler2D light_position;  // xyz, w = 1 where a surface was hit
layout(binding = 1) uniform sampler2D light_normal;    // faces the light
layout(binding = 2) uniform sampler2D light_albedo;
layout(binding = 3) uniform sampler2D camera_position;  // camera G-buffer, w = 0: background
layout(binding = 4) uniform sampler2D camera_normal;

layout(std430, binding = INDIRECT_PHOTONS_BINDING) writeonly restrict buffer Photons {
  Photon photons[];
};
layout(std430, binding = INDIRECT_COUNTERS_BINDING) restrict buffer PhotonCounters {
  uint photon_counters[];
};
// Per light texel: xyz the primary flux, and (next entry) the flux emitted into secondaries.
layout(std430, binding = INDIRECT_TALLY_BINDING) writeonly restrict buffer PhotonTally {
  vec4 photon_tally[];
};

uniform uint photon_capacity;
uniform int light_resolution;
uniform vec3 light_forward, light_right, light_up;  // unit axes of the light's image plane
uniform float light_tan_half;                        // tan(outer angle)
uniform mat4 camera_view_projection;
uniform vec3 camera_eye;
uniform float depth_threshold;  // scene units (default: a few LDM pixels, the hits' error)
uniform float footprint_threshold;  // max norm of s * D x, scene units
uniform float splat_scale;          // s
uniform float normal_offset_pixels;

uint counts[PHOTON_COUNTERS];

// Where x2 falls in the camera's image, and whether the camera sees it there: the distance
// from the eye to x2 within depth_threshold of the G-buffer's, and x2 on the lit side of the
// surface the camera sees.
// x2 is moved along n2 onto the plane of the surface point the camera sees there: the LDM
// hit lies at its LDM pixel's depth, up to a pixel times the slope off the surface, and the
// splat's kernel (its topological bias) measures distances from the photon's tangent plane.
bool camera_sees(inout vec3 x2, vec3 w_o, out vec3 n2) {
  const vec4 clip = camera_view_projection * vec4(x2, 1.0);
  n2 = vec3(0.0);
  if (!(clip.w > 0.0)) return false;
  const vec2 ndc = clip.xy / clip.w;
  if (any(greaterThanEqual(abs(ndc), vec2(1.0)))) return false;
  const ivec2 size = textureSize(camera_position, 0);
  const ivec2 pixel = min(ivec2((ndc * 0.5 + 0.5) * vec2(size)), size - 1);
  const vec4 seen = texelFetch(camera_position, pixel, 0);
  if (seen.w == 0.0) return false;
  if (distance(x2, camera_eye) > distance(seen.xyz, camera_eye) + depth_threshold) return false;
  n2 = texelFetch(camera_normal, pixel, 0).xyz;
  if (!(dot(n2, w_o) < 0.0)) return false;  // it arrives on the side the camera does not see
  x2 -= dot(x2 - seen.xyz, n2) * n2;
  return true;
}

void emit_secondary(uint texel_index, uint view, bool ahead, vec3 x1, vec3 n1, vec3 d1,
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
    return;
  }
  vec3 x2 = offset_x + t * w_o;
  vec3 n2;
  if (!camera_sees(x2, w_o, n2)) {
    ++counts[PHOTON_COUNT_CULLED_DEPTH];
    return;
  }
  PhotonDifferential p = primary;
  if (!photon_diffuse_reflect(p, -d1, w_o) || !photon_transfer(p, w_o, n2, distance(x1, x2)) ||
      !(photon_footprint_area(p) > 0.0)) {
    ++counts[PHOTON_COUNT_DEGENERATE];
    return;
  }
  const vec3 extent = max(abs(p.du_x), abs(p.dv_x)) * splat_scale;
  if (max(max(extent.x, extent.y), extent.z) > footprint_threshold) {
    ++counts[PHOTON_COUNT_CULLED_FOOTPRINT];
    return;
  }
  ++counts[PHOTON_COUNT_APPENDS];
  const uint id = atomicAdd(photon_counters[PHOTON_COUNT_APPENDS], 1u);
  if (id >= photon_capacity) return;  // overflow: counted by the counter, not stored
  photons[id].position = vec4(x2, uintBitsToFloat(texel_index));
  photons[id].normal = vec4(n2, uintBitsToFloat(view * 2u + (ahead ? 1u : 0u)));
  photons[id].du = vec4(p.du_x, 0.0);
  photons[id].dv = vec4(p.dv_x, 0.0);
  photons[id].flux = vec4(flux, 0.0);
}

void main() {
  const ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(texel, ivec2(light_resolution)))) return;
  for (uint i = 0u; i < PHOTON_COUNTERS; ++i) counts[i] = 0u;
  const uint texel_index = uint(texel.y * light_resolution + texel.x);
  photon_tally[2u * texel_index] = vec4(0.0);
  photon_tally[2u * texel_index + 1u] = vec4(0.0);

  // The texel centre's direction; the spot's cone is the image's inscribed circle.
  const vec2 ndc = (vec2(texel) + 0.5) / float(light_resolution) * 2.0 - 1.0;
  const vec4 hit = texelFetch(light_position, texel, 0);
  if (dot(ndc, ndc) > 1.0 || hit.w == 0.0) return;
  const vec3 d_hat = light_forward + light_tan_half * (ndc.x * light_right + ndc.y * light_up);
  const float texel_side = 2.0 * light_tan_half / float(light_resolution);
  // Flux through the texel: I(d) times its solid angle, texel area * cos^3 on the plane at 1.
  const float d_len = length(d_hat);
  const vec3 primary_flux =
      spot_radiant_intensity(d_hat) * (texel_side * texel_side / (d_len * d_len * d_len));
  ++counts[PHOTON_COUNT_PRIMARY];
  photon_tally[2u * texel_index] = vec4(primary_flux, 1.0);

  const vec3 d1 = d_hat / d_len;
  const vec3 x1 = hit.xyz;
  const vec3 n1 = texelFetch(light_normal, texel, 0).xyz;
  PhotonDifferential primary =
      photon_at_light(d_hat, texel_side * light_right, texel_side * light_up);
  if (!photon_transfer(primary, d1, n1, distance(spot_position, x1))) {
    ++counts[PHOTON_COUNT_PRIMARY_DEGENERATE];
  } else {
    const vec3 reflected = primary_flux * texelFetch(light_albedo, texel, 0).rgb;  // rho * Phi1
    vec3 emitted = vec3(0.0);
    for (uint view = 0u; view < LDM_VIEW_COUNT; ++view) {
      const float cos_o = dot(ldm_views[view].forward.xyz, n1);
      if (cos_o == 0.0) continue;  // tangent: neither side is in the hemisphere
      // rho/pi * Phi1 * |cos| * 2 pi / N
      const vec3 flux = reflected * (2.0 * abs(cos_o) / float(LDM_VIEW_COUNT));
      ++counts[PHOTON_COUNT_EMITTED];
      emitted += flux;
      const uint before = trace_steps_so_far();
      emit_secondary(texel_index, view, cos_o > 0.0, x1, n1, d1, primary, flux);
      trace_steps_max(view, trace_steps_so_far() - before);
    }
    trace_steps_max(LDM_VIEW_COUNT, trace_steps_so_far() + LDM_VIEW_COUNT);
    photon_tally[2u * texel_index + 1u] = vec4(emitted, 0.0);
  }
  // The append counter is counted as it goes; the rest once per invocation.
  for (uint i = 1u; i < PHOTON_COUNTERS; ++i)
    if (counts[i] != 0u) atomicAdd(photon_counters[i], counts[i]);
}
