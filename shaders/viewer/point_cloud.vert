// Draws the points of point_cloud.comp from the viewer's camera, coloured by layer or view.
layout(location = 0) in vec4 in_point;

uniform mat4 camera_view_projection;
uniform uint colour_by_view;  // 0: by layer index, 1: by view
uniform float point_size;

out vec3 v_colour;

// A few well-separated hues, repeating.
vec3 palette(uint i) {
  const vec3 colours[8] = vec3[8](vec3(0.95, 0.25, 0.2), vec3(0.2, 0.75, 0.3),
                                  vec3(0.25, 0.45, 0.95), vec3(0.95, 0.8, 0.2),
                                  vec3(0.8, 0.3, 0.85), vec3(0.2, 0.85, 0.85),
                                  vec3(0.95, 0.55, 0.15), vec3(0.85, 0.85, 0.85));
  return colours[i % 8u];
}

void main() {
  if (in_point.w < 0.0) {  // an empty slot: outside the clip volume, never rasterised
    gl_Position = vec4(2.0, 2.0, 2.0, 1.0);
    v_colour = vec3(0);
    return;
  }
  const uint code = uint(in_point.w);
  v_colour = palette(colour_by_view != 0u ? code >> 16u : code & 0xffffu);
  gl_Position = camera_view_projection * vec4(in_point.xyz, 1.0);
  gl_PointSize = point_size;
}
