// The flux audit's splat (harness/passes/photon_lighting.h, SplatAudit): the splat of
// photon_splat.frag, over a quad PHOTON_SPLAT_QUAD_SCALE times as large, writing per pixel
// (summed by additive blending) the flux it deposits and what it would with less in the way,
// as irradiance (pi E K, Eq. 27's L without rho / pi) times the pixel's surface area, mean of
// RGB:
//   x  deposited: K(|M (x - x_p)|), inside the splat's own quad (what the image holds)
//   y  uncut: K of the in-plane distance alone (M's first two rows), inside the quad
//   z  the same times |n_x . n_p|: the pixel's area projected onto the photon's tangent
//      plane, inside the quad
//   w  as z, wherever the enlarged quad reaches
// "Inside the quad": the pixel centre's ray meets the photon's tangent plane inside the
// splat's quad x_p +- Du/2 +- Dv/2, as the rasteriser decides for the real splat.
layout(binding = 0) uniform sampler2D camera_position;
layout(binding = 2) uniform sampler2D camera_normal;
layout(binding = 3) uniform sampler2D pixel_area;  // the pixel's surface patch, scene units^2

uniform vec3 camera_eye;

flat in vec3 splat_position;
flat in vec3 splat_irradiance;
flat in mat3 splat_to_filter;
flat in vec3 splat_normal;
layout(location = 0) out vec4 out_audit;

float silverman(float l) {
  if (!(l < 1.0)) return 0.0;
  const float q = 1.0 - l * l;
  return 3.0 / 3.14159265358979 * q * q;
}

void main() {
  const ivec2 pixel = ivec2(gl_FragCoord.xy);
  const vec4 x = texelFetch(camera_position, pixel, 0);
  if (x.w == 0.0) discard;
  const vec3 f = splat_to_filter * (x.xyz - splat_position);
  const float area = texelFetch(pixel_area, pixel, 0).r;
  const float e = 3.14159265358979 * dot(splat_irradiance, vec3(1.0 / 3.0)) * area;
  const vec3 n_x = texelFetch(camera_normal, pixel, 0).xyz;
  const float tangent = e * silverman(length(f.xy)) * abs(dot(n_x, splat_normal));
  const vec3 v = x.xyz - camera_eye;
  const float vn = dot(v, splat_normal);
  bool inside = false;
  if (vn != 0.0) {
    const float t = dot(splat_position - camera_eye, splat_normal) / vn;
    const vec2 q = (splat_to_filter * (camera_eye + t * v - splat_position)).xy;
    inside = t > 0.0 && all(lessThanEqual(abs(q), vec2(1.0)));
  }
  out_audit = inside ? vec4(e * silverman(length(f)), e * silverman(length(f.xy)), tangent, tangent)
                     : vec4(0.0, 0.0, 0.0, tangent);
}
