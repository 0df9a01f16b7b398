// The LDM trace of thesis §3.3.1 and §4.4.1 (Listing 5), written once on the query API:
// project x into a view, walk the pixel's sorted fragments to the one nearest x (x's own
// surface), and return the distances from x to the fragments just before and just after it,
// i.e. to the first occluder along -forward and along +forward.
#include "common/ldm_query_api.glsl"

// +infinity: nothing in that direction. A define, not a const: uintBitsToFloat is not a
// constant expression for every GLSL compiler (glslang rejects it).
#define LDM_NO_HIT uintBitsToFloat(0x7f800000u)

struct LdmNeighbours {
  float behind;  // distance to the nearest fragment before x's own (smaller depth)
  float ahead;   // distance to the nearest fragment after it (larger depth)
};

LdmNeighbours ldm_neighbours(uint view_index, vec3 x) {
  const LdmView view = ldm_views[view_index];
  const vec3 p = x - view.eye.xyz;
  const vec2 ndc = vec2(dot(p, view.right.xyz), dot(p, view.up.xyz)) / view.right.w;
  LdmNeighbours result = LdmNeighbours(LDM_NO_HIT, LDM_NO_HIT);
  // Outside the view: assumed clear, as in the thesis (the view covers the whole scene).
  if (any(greaterThanEqual(abs(ndc), vec2(1.0)))) return result;
  const uvec2 texel = min(uvec2((ndc * 0.5 + 0.5) * vec2(view.dims.xy)), view.dims.xy - 1u);
  const float depth_x = dot(p, view.forward.xyz);

  float nearest = LDM_NO_HIT;
  bool want_next = false;
  uint steps = 0u;
  for (LdmCursor c = ldm_begin(ldm_pixel_index(view_index, texel));
       ldm_valid(c) && steps < LDM_MAX_LIST_LENGTH; c = ldm_next(c), ++steps) {
    const float distance = abs(ldm_depth(c) - depth_x);
    if (want_next) {
      want_next = false;
      result.ahead = distance;
    }
    if (distance < nearest) {  // still approaching x's own fragment
      result.behind = nearest;
      nearest = distance;
      want_next = true;
    } else {
      break;  // the list is sorted: distances only grow from here
    }
  }
  if (want_next) result.ahead = LDM_NO_HIT;  // x's fragment was the last one
  return result;
}
