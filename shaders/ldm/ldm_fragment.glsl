// Shared by the fragment stages of the LDM geometry passes: which LDM pixel a fragment
// belongs to. Fragment shaders here write only to storage buffers, never to a framebuffer.
#include "common/ldm_views.glsl"

uniform uint ldm_view_index;
in float v_depth;

uint ldm_fragment_pixel() {
  const LdmView view = ldm_views[ldm_view_index];
  const uvec2 texel = uvec2(gl_FragCoord.xy);
  return view.dims.z + texel.y * view.dims.x + texel.x;
}

// Helper invocations (which a rasteriser may run for whole 2x2 quads at triangle edges) must
// not take part: their stores and atomics have no effect and return undefined values, so an
// insertion loop in one would only spin to its step bound. Every LDM fragment shader that
// writes storage starts its main() with this.
#define LDM_SKIP_HELPER_INVOCATIONS \
  if (gl_HelperInvocation) return
