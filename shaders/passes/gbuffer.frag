#include "common/work_counters.glsl"
in vec3 v_position;
in vec3 v_normal;
uniform vec3 camera_eye;
layout(location = 0) out vec4 out_position;  // xyz world position, w = 1 (0: background)
layout(location = 1) out vec4 out_normal;    // xyz unit normal facing the camera
#if GBUFFER_ALBEDO
#include "passes/indirect/surface_albedo.glsl"
layout(location = 2) out vec4 out_albedo;    // rgb diffuse albedo (lighting passes)
#endif
#if GBUFFER_TRIANGLE_ID
layout(location = 3) out uint out_triangle;  // the scene triangle's index + 1 (0: background)
#endif

void main() {
#if WORK_COUNTING
  if (!gl_HelperInvocation) work_add(fragments, 1);
#endif
  vec3 n = normalize(v_normal);
  // Surfaces are two-sided: the normal faces the viewer (the reference renderer does the same).
  if (dot(n, camera_eye - v_position) < 0.0) n = -n;
  out_position = vec4(v_position, 1.0);
  out_normal = vec4(n, 0.0);
#if GBUFFER_ALBEDO
  out_albedo = vec4(surface_albedo(gl_PrimitiveID), 1.0);
#endif
#if GBUFFER_TRIANGLE_ID
  out_triangle = uint(gl_PrimitiveID) + 1u;
#endif
}
