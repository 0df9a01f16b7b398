// A textured rectangle of the viewer's window: the pass image, the reference or the error
// map, shown pixel for pixel (harness/viewer/image_panel.h).
uniform vec4 rect;  // x0, y0, x1, y1 in normalised device coordinates
out vec2 v_uv;
void main() {
  const vec2 corner = vec2(float(gl_VertexID & 1), float((gl_VertexID >> 1) & 1));
  v_uv = vec2(corner.x, 1.0 - corner.y);  // textures hold rows top first
  gl_Position = vec4(mix(rect.xy, rect.zw, corner), 0.0, 1.0);
}
