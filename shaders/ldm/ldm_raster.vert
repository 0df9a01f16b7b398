// Vertex stage of every LDM geometry pass (census, construction): orthographic projection
// into one LDM view and the linear depth along the view's forward axis. All views are drawn
// by one instanced draw call (ldm_impls/common/ldm_rasterizer.cpp): instance i is view i.
//
// `invariant gl_Position`: the census, the DF-buffer's count and store passes and every
// construction must rasterise exactly the same fragments, although they are different
// programs; without it a compiler may evaluate the projection differently per program.
#include "common/ldm_views.glsl"
// A counting variant whose fragment stage counts by blending (WORK_BLEND_TARGETS) still
// counts this stage's vertices with atomics: a vertex has no target to blend into.
#define WORK_ATOMICS_ONLY 1
#include "common/work_counters.glsl"

layout(location = 0) in vec3 in_position;
invariant gl_Position;
out float v_depth;
flat out uint v_view_index;

void main() {
  const uint view_index = uint(gl_InstanceID);
  const LdmView view = ldm_views[view_index];
  gl_Position = view.view_projection * vec4(in_position, 1.0);
  v_depth = dot(in_position - view.eye.xyz, view.forward.xyz);
  v_view_index = view_index;
  work_add(vertices, 1);
}
