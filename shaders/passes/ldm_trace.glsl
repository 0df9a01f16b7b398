// The LDM trace of thesis §3.3.1 and §4.4.1, written once on the query API: project x into a
// view, read the sorted fragments of its LDM pixel and return the distances from x to the
// first occluder along -forward (behind) and along +forward (ahead). How x's own surface is
// told apart from its occluders is the trace variant, chosen by the define LDM_TRACE (see
// harness/passes/ao_variants.h):
//
//  LDM_TRACE_LISTING5  thesis Listing 5: the fragment nearest x in depth is x's own surface;
//                      its neighbours in the list are the occluders. With the normal offset,
//                      x sits k·s·sin(a) off its surface, so at a concave corner the adjacent
//                      wall can be nearer in depth than x's own surface: the walk takes the
//                      wall for x's surface and the occluded directions come back clear.
//  LDM_TRACE_INTERVAL  no own-surface search: behind is the last fragment below x's depth,
//                      ahead the first one above it. x's own surface falls on the far side
//                      only if the normal offset lifts x clear of it (offset >= ~0.7 px).
//  LDM_TRACE_PLANE     predicts x's own surface depth at the LDM pixel centre from the surface
//                      point and its G-buffer normal and skips fragments within a slope-scaled
//                      tolerance of it; the rest split at x's depth as in `interval`. Needs no
//                      normal offset.
#include "common/ldm_query_api.glsl"

#define LDM_TRACE_LISTING5 0
#define LDM_TRACE_INTERVAL 1
#define LDM_TRACE_PLANE 2
#ifndef LDM_TRACE
#error "LDM_TRACE must name the trace variant (set by harness/passes/ao_pass.cpp)"
#endif
// The plane trace's tolerance, in LDM pixels: CONSTANT + SLOPE * tan(angle(n, forward)), the
// tangent capped at MAX_SLOPE. Set by the C++ side (harness/scene/ao_variants.h), which the
// tests share, so there is no second copy of the numbers here.
#if LDM_TRACE == LDM_TRACE_PLANE && (!defined(LDM_PLANE_TOLERANCE_CONSTANT) || !defined(LDM_PLANE_TOLERANCE_SLOPE) || !defined(LDM_PLANE_MAX_SLOPE))
#error "the plane trace needs LDM_PLANE_TOLERANCE_CONSTANT, _SLOPE and LDM_PLANE_MAX_SLOPE"
#endif

// +infinity: nothing in that direction. A define, not a const: uintBitsToFloat is not a
// constant expression for every GLSL compiler (glslang rejects it).
#define LDM_NO_HIT uintBitsToFloat(0x7f800000u)

// Iterations of the walks below this invocation has run (passes/trace_steps.glsl).
uint ldm_walk_steps = 0u;

struct LdmNeighbours {
  float behind;  // distance to the nearest occluder before x (smaller depth)
  float ahead;   // distance to the nearest occluder after x (larger depth)
};

// Fragments closer in depth than this are one surface: coplanar or duplicated triangles give
// pairs whose depths differ only by interpolation noise (or not at all), and the thesis's
// walk (Listing 5), which stops at the first distance that does not decrease, would then take
// x's own surface for its occluder. Relative to the depth range, far above float noise
// (~1e-7) and the HA-buffer's 24-bit quantum (6e-8), far below any real gap.
float ldm_coincident_depth(LdmView view) { return view.forward.w * (1.0 / 65536.0); }

// Listing 5's walk: `own` is the fragment nearest x so far (x's own surface); the fragment it
// replaces becomes the occluder behind, unless the two are one surface; the first fragment
// past own (and not one surface with it) is the occluder ahead.
LdmNeighbours ldm_walk_listing5(uint pixel, float depth_x, float coincident) {
  LdmNeighbours result = LdmNeighbours(LDM_NO_HIT, LDM_NO_HIT);
  bool have_own = false;
  float own = 0.0;
  uint steps = 0u;
  for (LdmCursor c = ldm_begin(pixel); ldm_valid(c) && steps < LDM_MAX_LIST_LENGTH;
       c = ldm_next(c), ++steps) {
    ++ldm_walk_steps;
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

// The interval walk: the fragments outside [skip_lo, skip_hi] split at x's depth. Fragments
// within `coincident` of x's depth belong to x (at a normal that faces the view axis the
// offset and the pixel-centre error both vanish, and float noise alone would decide).
LdmNeighbours ldm_walk_interval(uint pixel, float depth_x, float coincident, float skip_lo,
                                float skip_hi) {
  LdmNeighbours result = LdmNeighbours(LDM_NO_HIT, LDM_NO_HIT);
  uint steps = 0u;
  for (LdmCursor c = ldm_begin(pixel); ldm_valid(c) && steps < LDM_MAX_LIST_LENGTH;
       c = ldm_next(c), ++steps) {
    ++ldm_walk_steps;
    const float depth = ldm_depth(c);
    if (depth >= skip_lo && depth <= skip_hi) continue;  // x's own surface (plane trace)
    if (depth < depth_x - coincident) {
      result.behind = depth_x - depth;  // the last one below x wins
    } else if (depth > depth_x + coincident) {
      result.ahead = depth - depth_x;   // the first one above x
      break;
    }
  }
  return result;
}

// x: the point traced from (the surface point, moved by the normal offset); surface and n:
// the G-buffer's surface point and normal (used by the plane trace only).
LdmNeighbours ldm_neighbours(uint view_index, vec3 x, vec3 surface, vec3 n) {
  const LdmView view = ldm_views[view_index];
  const vec3 p = x - view.eye.xyz;
  const vec2 ndc = vec2(dot(p, view.right.xyz), dot(p, view.up.xyz)) / view.right.w;
  // Outside the view: assumed clear, as in the thesis (the view covers the whole scene).
  if (any(greaterThanEqual(abs(ndc), vec2(1.0)))) return LdmNeighbours(LDM_NO_HIT, LDM_NO_HIT);
  const uvec2 texel = min(uvec2((ndc * 0.5 + 0.5) * vec2(view.dims.xy)), view.dims.xy - 1u);
  const uint pixel = ldm_pixel_index(view_index, texel);
  const float depth_x = dot(p, view.forward.xyz);
  const float coincident = ldm_coincident_depth(view);
#if LDM_TRACE == LDM_TRACE_LISTING5
  return ldm_walk_listing5(pixel, depth_x, coincident);
#elif LDM_TRACE == LDM_TRACE_INTERVAL
  return ldm_walk_interval(pixel, depth_x, coincident, 1.0, 0.0);  // empty skip range
#elif LDM_TRACE == LDM_TRACE_PLANE
  // The pixel centre's ray c + t forward meets the plane through `surface` with normal n at
  // t = depth(surface) - n.(c - surface) / n.forward, c - surface taken in the image plane.
  const vec2 centre_ndc = (vec2(texel) + 0.5) / vec2(view.dims.xy) * 2.0 - 1.0;
  const vec3 s = surface - view.eye.xyz;
  const vec2 lateral = centre_ndc * view.right.w -
                       vec2(dot(s, view.right.xyz), dot(s, view.up.xyz));
  const vec3 to_centre = lateral.x * view.right.xyz + lateral.y * view.up.xyz;
  const float cos_a = abs(dot(n, view.forward.xyz));
  const float tan_a = min(sqrt(max(0.0, 1.0 - cos_a * cos_a)) / max(cos_a, 1e-6),
                          LDM_PLANE_MAX_SLOPE);
  if (cos_a * LDM_PLANE_MAX_SLOPE < 1.0)  // grazing: the plane says nothing at this pixel
    return ldm_walk_interval(pixel, depth_x, coincident, 1.0, 0.0);
  const float own = dot(s, view.forward.xyz) - dot(n, to_centre) / dot(n, view.forward.xyz);
  const float tolerance =
      coincident +
      view.eye.w * (LDM_PLANE_TOLERANCE_CONSTANT + LDM_PLANE_TOLERANCE_SLOPE * tan_a);
  return ldm_walk_interval(pixel, depth_x, coincident, own - tolerance, own + tolerance);
#else
#error "LDM_TRACE: unknown trace variant"
#endif
}
