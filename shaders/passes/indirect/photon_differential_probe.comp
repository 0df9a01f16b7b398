// Evaluates photon_differential.glsl's functions on the degenerate cases a trace can meet
// (tests/indirect: each must be reported, never return NaN or infinity).
#include "passes/indirect/photon_differential.glsl"
layout(local_size_x = 1) in;
layout(std430, binding = LDM_PASS_BINDING0) writeonly restrict buffer ProbeResults {
  uint ok[8];
  vec4 values[8];
};

void main() {
  const PhotonDifferential p = photon_at_light(vec3(0.0, 0.0, -1.0), vec3(0.01, 0.0, 0.0),
                                               vec3(0.0, 0.01, 0.0));
  // 0: a regular transfer onto a plane facing the ray succeeds, area (0.01 t)^2.
  PhotonDifferential a = p;
  ok[0] = photon_transfer(a, vec3(0.0, 0.0, -1.0), vec3(0.0, 0.0, 1.0), 2.0) ? 1u : 0u;
  values[0] = vec4(photon_footprint_area(a), a.du_x);
  // 1: grazing: d . n = 0.
  PhotonDifferential b = p;
  ok[1] = photon_transfer(b, vec3(0.0, 0.0, -1.0), vec3(1.0, 0.0, 0.0), 2.0) ? 1u : 0u;
  // 2: nearly grazing, below PHOTON_MIN_COS.
  PhotonDifferential c = p;
  ok[2] = photon_transfer(c, vec3(0.0, 0.0, -1.0), normalize(vec3(1.0, 0.0, 1e-4)), 2.0) ? 1u : 0u;
  // 3: an infinite distance.
  PhotonDifferential d = p;
  ok[3] = photon_transfer(d, vec3(0.0, 0.0, -1.0), vec3(0.0, 0.0, 1.0), uintBitsToFloat(0x7f800000u)) ? 1u : 0u;
  // 4: a rotation between opposite (parallel) directions.
  PhotonDifferential e = p;
  ok[4] = photon_diffuse_reflect(e, vec3(0.0, 1.0, 0.0), vec3(0.0, -1.0, 0.0)) ? 1u : 0u;
  // 5: a regular rotation keeps the differential's length.
  PhotonDifferential f = p;
  ok[5] = photon_diffuse_reflect(f, vec3(0.0, 0.0, 1.0), vec3(0.0, 1.0, 0.0)) ? 1u : 0u;
  values[5] = vec4(length(f.du_d), length(p.du_d), f.du_d.y, f.dv_d.z);
  // 6: a collapsed footprint (D_v x parallel to D_u x) has zero area.
  PhotonDifferential g = p;
  g.du_x = vec3(1.0, 0.0, 0.0);
  g.dv_x = vec3(2.0, 0.0, 0.0);
  values[6] = vec4(photon_footprint_area(g));
  ok[6] = photon_footprint_area(g) > 0.0 ? 1u : 0u;
  ok[7] = 1u;
}
