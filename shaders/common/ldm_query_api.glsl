// The GLSL query API every LDM structure implements (in shaders/ldm/<name>/query.glsl).
// Passes read structures only through it, so a pass is written once for all of them.
//
//   struct LdmCursor { ... };             position in one pixel's depth-sorted fragments
//   LdmCursor ldm_begin(uint pixel);      nearest fragment of the pixel; `pixel` indexes all
//                                         views' pixels: ldm_views[v].dims.z + y * R + x
//   bool  ldm_valid(LdmCursor c);         false once past the farthest fragment
//   float ldm_depth(LdmCursor c);         depth along the view's forward axis (scene units)
//   LdmCursor ldm_next(LdmCursor c);      the next fragment in ascending depth
//   void  ldm_work_flush();               adds what this invocation's queries counted to
//                                         the work counters (the counting replay: the
//                                         queries tally, common/work_counters.glsl); a pass
//                                         calls it once, after its last query
//
// Fragments come out in ascending depth (ties in any order). LDM_MAX_LIST_LENGTH (a define,
// the scene's measured maximum depth complexity) bounds every walk, so that a corrupted
// structure cannot hang a pass; the inspector reports lists that reach the bound.
#ifndef LDM_QUERY_API_GLSL
#define LDM_QUERY_API_GLSL
#include "common/ldm_views.glsl"

// Iterations of a structure's own loops inside ldm_begin()/ldm_next() (the HA-buffer's probe
// along its ages), counted for the passes that bound what one invocation loops
// (passes/trace_steps.glsl: llvmpipe ends every loop of an invocation silently after 65,535
// iterations in all). A structure marks each such iteration with LDM_COUNT_QUERY_STEP().
uint ldm_query_loop_steps = 0u;
#define LDM_COUNT_QUERY_STEP() (++ldm_query_loop_steps)

// Index of LDM pixel `texel` of view `view` in all-view arrays.
uint ldm_pixel_index(uint view, uvec2 texel) {
  return ldm_views[view].dims.z + texel.y * ldm_views[view].dims.x + texel.x;
}

#endif
