// The lit image: direct + indirect.
#include "common/work_counters.glsl"
layout(binding = 0) uniform sampler2D direct_radiance;
layout(binding = 1) uniform sampler2D indirect_radiance;
layout(location = 0) out vec4 out_radiance;
void main() {
  const ivec2 pixel = ivec2(gl_FragCoord.xy);
  work_add(fragments, 1);
  out_radiance = texelFetch(direct_radiance, pixel, 0) + texelFetch(indirect_radiance, pixel, 0);
}
