// The splatting draw's vertex count, min(appends, capacity), written on the GPU so that the
// draw needs no read-back (DrawArraysIndirectCommand: count, instances, first, base instance).
#include "passes/indirect/photon.glsl"
layout(local_size_x = 1) in;
layout(std430, binding = INDIRECT_COUNTERS_BINDING) readonly restrict buffer PhotonCounters {
  uint photon_counters[];
};
layout(std430, binding = INDIRECT_DRAW_BINDING) writeonly restrict buffer DrawCommand {
  uint draw_command[4];
};
uniform uint photon_capacity;
void main() {
  draw_command[0] = min(photon_counters[PHOTON_COUNT_APPENDS], photon_capacity);
  draw_command[1] = 1u;
  draw_command[2] = 0u;
  draw_command[3] = 0u;
}
