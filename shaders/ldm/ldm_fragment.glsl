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
