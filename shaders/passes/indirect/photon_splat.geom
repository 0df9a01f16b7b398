// Photon splatting, geometry stage: the point becomes the quad spanned by its scaled
// positional differential, x_p +- Du/2 +- Dv/2 (Listing 11), projected by the camera. The
// flux audit (PHOTON_SPLAT_AUDIT) draws it PHOTON_SPLAT_QUAD_SCALE times as large and passes
// the photon's normal on.
#ifndef PHOTON_SPLAT_QUAD_SCALE
#define PHOTON_SPLAT_QUAD_SCALE 1.0
#endif
#include "common/work_counters.glsl"
layout(points) in;
layout(triangle_strip, max_vertices = 4) out;

in PhotonSplat {
  vec3 position;
  vec3 du, dv;
  vec3 irradiance;
  mat3 to_filter;
#ifdef PHOTON_SPLAT_AUDIT
  vec3 normal;
#endif
} photon[];

uniform mat4 camera_view_projection;

flat out vec3 splat_position;
flat out vec3 splat_irradiance;
flat out mat3 splat_to_filter;
#ifdef PHOTON_SPLAT_AUDIT
flat out vec3 splat_normal;
#endif

void corner(float su, float sv) {
  splat_position = photon[0].position;
  splat_irradiance = photon[0].irradiance;
  splat_to_filter = photon[0].to_filter;
#ifdef PHOTON_SPLAT_AUDIT
  splat_normal = photon[0].normal;
#endif
  const vec3 x = photon[0].position +
                 (0.5 * PHOTON_SPLAT_QUAD_SCALE) * (su * photon[0].du + sv * photon[0].dv);
  gl_Position = camera_view_projection * vec4(x, 1.0);
  EmitVertex();
}

void main() {
  work_add(quads, 1);
  corner(-1.0, -1.0);
  corner(-1.0, 1.0);
  corner(1.0, -1.0);
  corner(1.0, 1.0);
  EndPrimitive();
}
