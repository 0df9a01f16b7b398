// The raster-only baseline: the LDM geometry pass with nothing stored.
#include "ldm/ldm_fragment.glsl"

void main() {}
