// Photon splatting (thesis §5.4.2), vertex stage: one point per stored photon, read from the
// photon buffer by index. Scales the differential by s, builds the matrix M into filter
// coordinates and the irradiance estimate E = Phi / A_p (Eq. 24, A_p = pi/4 |s Du x s Dv|).
#include "passes/indirect/photon.glsl"
#include "common/work_counters.glsl"

layout(std430, binding = INDIRECT_PHOTONS_BINDING) readonly restrict buffer Photons {
  Photon photons[];
};
uniform float splat_scale;      // s
uniform float topological_bias; // a

out PhotonSplat {
  vec3 position;
  vec3 du, dv;
  vec3 irradiance;
  mat3 to_filter;  // M
#ifdef PHOTON_SPLAT_AUDIT
  vec3 normal;
#endif
} photon;

void main() {
  work_add(vertices, 1);
  const Photon p = photons[gl_VertexID];
  const vec3 n = p.normal.xyz;
  const vec3 du = p.du.xyz * splat_scale;
  const vec3 dv = p.dv.xyz * splat_scale;
  photon.position = p.position.xyz;
  photon.du = du;
  photon.dv = dv;
  const float area = length(cross(du, dv));  // > 0: degenerate photons were not stored
  photon.irradiance = p.flux.rgb / (0.25 * 3.14159265358979 * area);
  // Rows (Eq. 26): (Dv x n, n x Du) * 2 / (Du . (Dv x n)) map the footprint's inscribed ellipse
  // (semi-axes Du/2, Dv/2) onto the unit disc; the third, a * n / r with r = sqrt(area) / 2
  // the footprint's mean semi-axis, reaches the kernel's edge a footprint radius / a off the
  // photon's tangent plane (the topological bias; docs/design/departures.md).
  const float det = dot(du, cross(dv, n));
  const vec3 row0 = cross(dv, n) * (2.0 / det);
  const vec3 row1 = cross(n, du) * (2.0 / det);
  const vec3 row2 = n * (topological_bias / (0.5 * sqrt(area)));
  photon.to_filter = transpose(mat3(row0, row1, row2));
#ifdef PHOTON_SPLAT_AUDIT
  photon.normal = n;
#endif
  gl_Position = vec4(0.0, 0.0, 0.0, 1.0);
}
