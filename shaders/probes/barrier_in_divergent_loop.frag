// The probe of barrier_in_divergent_loop.glsl in the fragment stage: one fragment per pixel
// of a PROBE_SIDE x PROBE_SIDE framebuffer without attachments (passes/fullscreen.vert).
#include "probes/barrier_in_divergent_loop.glsl"

void main() {
  const uvec2 pixel = uvec2(gl_FragCoord.xy);
  probe_invocation(pixel.y * uint(PROBE_SIDE) + pixel.x);
}
