// The LDM trace of thesis §3.3.1 and §4.4.1 (Listing 5), written once on the query API:
// project x into a view, walk the pixel's sorted fragments to the one nearest x (x's own
// surface), and return the distances from x to the fragments just before and just after it,
// i.e. to the first occluder along -forward and along +forward. Unlike Listing 5, fragments
// that coincide in depth count as one surface (see ldm_coincident_depth).
#include "common/ldm_query_api.glsl"

// +infinity: nothing in that direction. A define, not a const: uintBitsToFloat is not a
// constant expression for every GLSL compiler (glslang rejects it).
#define LDM_NO_HIT uintBitsToFloat(0x7f800000u)

struct LdmNeighbours {
  float behind;  // distance to the nearest fragment before x's own (smaller depth)
  float ahead;   // distance to the nearest fragment after it (larger depth)
};

// Fragments closer in depth than this are one surface: coplanar or duplicated triangles give
// pairs whose depths differ only by interpolation noise (or not at all), and the thesis's
// walk (Listing 5), which stops at the first distance that does not decrease, would then take
// x's own surface for its occluder. Relative to the depth range, far above float noise
// (~1e-7) and the HA-buffer's 24-bit quantum (6e-8), far below any real gap.
float ldm_coincident_depth(LdmView view) { return view.forward.w * (1.0 / 65536.0); }

LdmNeighbours ldm_neighbours(uint view_index, vec3 x) {
  const LdmView view = ldm_views[view_index];
  const vec3 p = x - view.eye.xyz;
  const vec2 ndc = vec2(dot(p, view.right.xyz), dot(p, view.up.xyz)) / view.right.w;
  LdmNeighbours result = LdmNeighbours(LDM_NO_HIT, LDM_NO_HIT);
  // Outside the view: assumed clear, as in the thesis (the view covers the whole scene).
  if (any(greaterThanEqual(abs(ndc), vec2(1.0)))) return result;
  const uvec2 texel = min(uvec2((ndc * 0.5 + 0.5) * vec2(view.dims.xy)), view.dims.xy - 1u);
  const float depth_x = dot(p, view.forward.xyz);
  const float coincident = ldm_coincident_depth(view);

  // Walk the sorted fragments: `own` is the one nearest x so far (x's own surface); the
  // fragment it replaces becomes the occluder behind, unless the two are one surface; the
  // first fragment past own (and not one surface with it) is the occluder ahead.
  bool have_own = false;
  float own = 0.0;
  uint steps = 0u;
  for (LdmCursor c = ldm_begin(ldm_pixel_index(view_index, texel));
       ldm_valid(c) && steps < LDM_MAX_LIST_LENGTH; c = ldm_next(c), ++steps) {
    const float depth = ldm_depth(c);
    if (!have_own) {
      own = depth;
      have_own = true;
    } else if (abs(depth - depth_x) < abs(own - depth_x)) {  // still approaching x
      if (depth > own + coincident) result.behind = abs(depth_x - own);
      own = depth;
    } else if (depth > own + coincident) {  // past x's own surface: the first occluder ahead
      result.ahead = abs(depth - depth_x);
      break;
    }
  }
  return result;
}
