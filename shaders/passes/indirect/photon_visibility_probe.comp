// camera_sees (photon_visibility.glsl) on given points, with the trace's own uniforms
// (PhotonLighting::probe_visibility, for tests of the depth test at its threshold): entry 2i
// holds a hit x2 (xyz), entry 2i + 1 the photon's direction of travel; the verdict is written
// into x2's w (as uint bits: 0 seen, else a PHOTON_TALLY_* fate).
layout(local_size_x = 1) in;
layout(binding = 3) uniform sampler2D camera_position;
layout(binding = 4) uniform sampler2D camera_normal;
#include "passes/indirect/photon_visibility.glsl"
layout(std430, binding = INDIRECT_PHOTONS_BINDING) restrict buffer Probe {
  vec4 probe[];
};

void main() {
  const uint i = gl_GlobalInvocationID.x;
  vec3 x2 = probe[2u * i].xyz;
  vec3 n2;
  const uint verdict = camera_sees(x2, probe[2u * i + 1u].xyz, n2);
  probe[2u * i].w = uintBitsToFloat(verdict);
}
