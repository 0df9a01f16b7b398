// Photon differentials (thesis §5.1.4 and §5.3.1, after Igehy 1999 and Schjøth et al. 2007):
// a ray r = (x, d) with the derivatives of x and d with respect to the light's image-plane
// coordinates u and v. Every function reports a degenerate case (a grazing transfer, a
// rotation between opposite directions, a non-finite result) by returning false, so that the
// caller culls and counts the photon instead of storing NaN or infinity.
#ifndef PHOTON_DIFFERENTIAL_GLSL
#define PHOTON_DIFFERENTIAL_GLSL

struct PhotonDifferential {
  vec3 du_x, dv_x, du_d, dv_d;
};

// |cos| below which a transfer onto a surface is grazing: D_u t divides by d.n.
#define PHOTON_MIN_COS 1e-3

bool finite3(vec3 v) { return !any(isnan(v)) && !any(isinf(v)); }

// At the light (a pinhole): D x = 0; D d is the derivative of normalize(d_hat) along the
// image-plane axes `du_axis`, `dv_axis` (the image plane's right and up, each scaled to one
// texel), d_hat the unnormalised direction through the texel (Listing 7's formula).
PhotonDifferential photon_at_light(vec3 d_hat, vec3 du_axis, vec3 dv_axis) {
  const float dd = dot(d_hat, d_hat);
  const float norm3 = dd * sqrt(dd);
  PhotonDifferential p;
  p.du_x = vec3(0.0);
  p.dv_x = vec3(0.0);
  p.du_d = (dd * du_axis - dot(d_hat, du_axis) * d_hat) / norm3;
  p.dv_d = (dd * dv_axis - dot(d_hat, dv_axis) * d_hat) / norm3;
  return p;
}

// Transfer along unit d by t onto a surface with normal n (Listing 8).
bool photon_transfer(inout PhotonDifferential p, vec3 d, vec3 n, float t) {
  const float dn = dot(d, n);
  if (abs(dn) < PHOTON_MIN_COS) return false;  // grazing
  const vec3 du = p.du_x + t * p.du_d;
  const vec3 dv = p.dv_x + t * p.dv_d;
  p.du_x = du - dot(du, n) / dn * d;
  p.dv_x = dv - dot(dv, n) / dn * d;
  return finite3(p.du_x) && finite3(p.dv_x);
}

// The rotation quaternion taking unit w_i to unit w_o (Sam 2014: axis w_i x w_o, w = 1 +
// w_i.w_o, normalised); undefined for opposite directions.
bool rotation_between(vec3 w_i, vec3 w_o, out vec4 q) {
  q = vec4(cross(w_i, w_o), 1.0 + dot(w_i, w_o));
  const float len = length(q);
  if (!(len > 1e-4)) return false;  // w_o = -w_i: no unique rotation
  q /= len;
  return true;
}

vec3 rotate(vec4 q, vec3 v) { return v + 2.0 * cross(q.xyz, cross(q.xyz, v) + q.w * v); }

// Diffuse reflection (§5.3.1): the position's differential is unchanged, the direction's is
// rotated as w_i is rotated onto w_o (Listing 9).
bool photon_diffuse_reflect(inout PhotonDifferential p, vec3 w_i, vec3 w_o) {
  vec4 q;
  if (!rotation_between(w_i, w_o, q)) return false;
  p.du_d = rotate(q, p.du_d);
  p.dv_d = rotate(q, p.dv_d);
  return true;
}

// The footprint parallelogram's area |D_u x x D_v x|.
float photon_footprint_area(PhotonDifferential p) { return length(cross(p.du_x, p.dv_x)); }

#endif
