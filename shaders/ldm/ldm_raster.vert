// Vertex stage of every LDM geometry pass (census, construction): orthographic projection
// into view `ldm_view_index` and the linear depth along the view's forward axis.
#include "common/ldm_views.glsl"

layout(location = 0) in vec3 in_position;
uniform uint ldm_view_index;
out float v_depth;

void main() {
  const LdmView view = ldm_views[ldm_view_index];
  gl_Position = view.view_projection * vec4(in_position, 1.0);
  v_depth = dot(in_position - view.eye.xyz, view.forward.xyz);
}
