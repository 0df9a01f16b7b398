// G-buffer from the user's camera: world position and shading normal per pixel.
#include "common/work_counters.glsl"
layout(location = 0) in vec3 in_position;
layout(location = 1) in vec3 in_normal;
uniform mat4 camera_view_projection;
out vec3 v_position;
out vec3 v_normal;

void main() {
  work_add(vertices, 1);
  v_position = in_position;
  v_normal = in_normal;
  gl_Position = camera_view_projection * vec4(in_position, 1.0);
}
