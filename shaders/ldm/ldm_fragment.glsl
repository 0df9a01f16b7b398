// Shared by the fragment stages of the LDM geometry passes: which LDM pixel a fragment
// belongs to. Fragment shaders here write only to storage buffers, never to a framebuffer.
//
// The same fragment shaders also run as compute shaders on a synthetic fragment list
// (LDM_SYNTHETIC_FRAGMENTS, ldm_impls/common/synthetic_fragments.h), for contention tests that
// a rasteriser shading one tile in order never produces: there the pixel, depth and view
// come from globals that the compute wrapper (ldm/synthetic_fragments.comp) sets.
#include "common/ldm_views.glsl"
#include "common/work_counters.glsl"

#if LDM_SYNTHETIC_FRAGMENTS
uint ldm_synthetic_pixel;  // the fragment's pixel over all views (ldm_pixel_index)
float v_depth;
uint v_view_index;

uint ldm_fragment_pixel() { return ldm_synthetic_pixel; }

// A compute invocation is never a helper invocation. (Every fragment is counted here.)
#define LDM_SKIP_HELPER_INVOCATIONS work_add(fragments, 1)

// Counts a retry of a lock-free insertion (a failed compare-and-swap) so that the contention
// tests can show the retry path ran. Compiles to nothing in the geometry pass.
layout(std430, binding = LDM_SYNTHETIC_RETRY_BINDING) restrict buffer LdmSyntheticRetries {
  uint ldm_synthetic_retries;
};
#define LDM_COUNT_RETRY() atomicAdd(ldm_synthetic_retries, 1u)
#else
in float v_depth;
flat in uint v_view_index;  // the draw instance: ldm_raster.vert draws view i as instance i

uint ldm_fragment_pixel() {
  const LdmView view = ldm_views[v_view_index];
  const uvec2 texel = uvec2(gl_FragCoord.xy);
  return view.dims.z + texel.y * view.dims.x + texel.x;
}

// Helper invocations (which a rasteriser may run for whole 2x2 quads at triangle edges) must
// not take part: their stores and atomics have no effect and return undefined values, so an
// insertion loop in one would only spin to its step bound. Every LDM fragment shader that
// writes storage starts its main() with this.
// (It is also where the counting replay counts the fragments shaded, and where a counting
// variant that counts by blending zeroes its outputs: work_counters.glsl.)
#define LDM_SKIP_HELPER_INVOCATIONS \
  WORK_BLEND_BEGIN();                      \
  if (gl_HelperInvocation) return;         \
  work_add(fragments, 1)

#define LDM_COUNT_RETRY()
#endif
