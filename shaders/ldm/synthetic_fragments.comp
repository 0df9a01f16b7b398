// Runs a fragment shader of the LDM geometry pass as a compute shader, once for every entry
// of a synthetic fragment list (ldm_impls/common/synthetic_fragments.h). The fragment shader
// is prepended to this file with `main` renamed to ldm_fragment_main (a define), so its code
// runs unchanged; ldm/ldm_fragment.glsl gives it its pixel, depth and view from the globals
// set here. Invocations of one work group run side by side, and work groups in parallel, so
// fragments of one pixel really do race, unlike under a rasteriser that shades a tile's
// fragments in order.
#undef main
layout(local_size_x = 64) in;

#include "ldm/ldm_fragment.glsl"
#include "ldm/common/compute_grid.glsl"

// (pixel over all views, float bits of the depth) per fragment.
layout(std430, binding = LDM_SYNTHETIC_FRAGMENTS_BINDING) readonly restrict buffer
    LdmSyntheticFragments {
  uvec2 ldm_synthetic_fragments[];
};

void main() {
  const uint i = linear_invocation_index();
  if (i >= LDM_SYNTHETIC_FRAGMENT_COUNT) return;
  const uvec2 fragment = ldm_synthetic_fragments[i];
  ldm_synthetic_pixel = fragment.x;
  v_depth = uintBitsToFloat(fragment.y);
  v_view_index = fragment.x / LDM_SYNTHETIC_PIXELS_PER_VIEW;
  ldm_fragment_main();
}
