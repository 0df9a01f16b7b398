// Linear indices over the two-dimensional workgroup grid of dispatch_linear_groups()
// (ldm_impls/common/compute_grid.h): rows of gl_NumWorkGroups.x groups.
#ifndef LDM_COMPUTE_GRID_GLSL
#define LDM_COMPUTE_GRID_GLSL

uint linear_workgroup_index() {
  return gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x;
}

uint linear_invocation_index() {
  return linear_workgroup_index() * gl_WorkGroupSize.x + gl_LocalInvocationID.x;
}

#endif
