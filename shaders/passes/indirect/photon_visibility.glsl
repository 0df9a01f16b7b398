// Whether the camera sees a secondary photon's hit x2 (thesis §5.4.1 step (b)), shared by the
// photon trace and its test probe. Needs, bound by the includer: the camera G-buffer's
// positions (w = 0: background) and normals as `camera_position` and `camera_normal`, and
// the uniforms below.
#ifndef PHOTON_VISIBILITY_GLSL
#define PHOTON_VISIBILITY_GLSL
#include "passes/indirect/photon.glsl"

uniform mat4 camera_view_projection;
uniform vec3 camera_eye;
uniform float depth_threshold;  // scene units (default: a few LDM pixels, the hits' error)

// The verdicts: seen, or one of the culled fates of the flux tally.
#define PHOTON_SEEN 0u

// Where x2 falls in the camera's image, and whether the camera sees it there: x2 within
// depth_threshold of the surface the camera sees at that pixel (else it is hidden), and on the
// lit side of that surface (w_o, the photon's direction of travel, against its normal).
// "Within": the thesis's test, x2 at most depth_threshold farther from the eye than the
// G-buffer's point.
// x2 is moved along n2 onto the plane of the surface point the camera sees there: the LDM
// hit lies at its LDM pixel's depth, up to a pixel times the slope off the surface, and the
// splat's kernel (its topological bias) measures distances from the photon's tangent plane.
uint camera_sees(inout vec3 x2, vec3 w_o, out vec3 n2) {
  const vec4 clip = camera_view_projection * vec4(x2, 1.0);
  n2 = vec3(0.0);
  if (!(clip.w > 0.0)) return PHOTON_TALLY_CULLED_OUTSIDE;
  const vec2 ndc = clip.xy / clip.w;
  if (any(greaterThanEqual(abs(ndc), vec2(1.0)))) return PHOTON_TALLY_CULLED_OUTSIDE;
  const ivec2 size = textureSize(camera_position, 0);
  const ivec2 pixel = min(ivec2((ndc * 0.5 + 0.5) * vec2(size)), size - 1);
  const vec4 seen = texelFetch(camera_position, pixel, 0);
  if (seen.w == 0.0) return PHOTON_TALLY_CULLED_OUTSIDE;
  n2 = texelFetch(camera_normal, pixel, 0).xyz;
  if (distance(x2, camera_eye) > distance(seen.xyz, camera_eye) + depth_threshold)
    return PHOTON_TALLY_CULLED_HIDDEN;
  if (!(dot(n2, w_o) < 0.0)) return PHOTON_TALLY_CULLED_BACKSIDE;
  x2 -= dot(x2 - seen.xyz, n2) * n2;
  return PHOTON_SEEN;
}
#endif
