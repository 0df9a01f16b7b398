// For BuildStats (never timed): the highest age + 1 over every pixel's ha_age_counts, reduced
// per work group in shared memory so that only one atomic per group reaches the buffer.
layout(local_size_x = 256) in;

layout(std430, binding = LDM_STRUCTURE_BINDING2) readonly restrict buffer HaAgeCounts {
  uint ha_age_counts[];
};
layout(std430, binding = LDM_STRUCTURE_BINDING3) restrict buffer HaAgeSummary {
  uint ha_highest_age_count;
};

shared uint group_highest;

void main() {
  if (gl_LocalInvocationIndex == 0u) group_highest = 0u;
  barrier();
  const uint pixel = gl_GlobalInvocationID.y * (gl_NumWorkGroups.x * 256u) + gl_GlobalInvocationID.x;
  if (pixel < LDM_HEADS_TOTAL) atomicMax(group_highest, ha_age_counts[pixel]);
  barrier();
  if (gl_LocalInvocationIndex == 0u) atomicMax(ha_highest_age_count, group_highest);
}
