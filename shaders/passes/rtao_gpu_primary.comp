// The GPU ray tracer's G-buffer (harness/passes/rtao_gpu.h, rtao_gpu:primary=trace): per
// pixel the primary ray through its centre, traced through the BVH (bvh_traversal.glsl) to
// its closest hit, and the surface point found there exactly as the reference finds it
// (harness/reference/surface_point.cpp): the position interpolated from the hit triangle's
// vertices with the hit's barycentrics, the interpolated vertex normal normalised (the plane's
// normal where it vanishes) and turned towards the camera, and the triangle. The same targets
// as the rasterised G-buffer (gbuffer.frag), which differs from the reference's primary rays
// at silhouettes (the rasteriser snaps vertices to its sub-pixel grid).
layout(local_size_x = 8, local_size_y = 8) in;

#include "passes/bvh_traversal.glsl"

layout(std430, binding = RTAO_GPU_SCENE_NORMALS_BINDING) restrict readonly buffer SceneNormals {
  float scene_normals[];  // per vertex, xyz packed (GpuScene's normal buffer)
};
layout(std430, binding = RTAO_GPU_SCENE_INDICES_BINDING) restrict readonly buffer SceneIndices {
  uint scene_indices[];  // per triangle, 3 vertex indices (GpuScene's index buffer)
};
layout(binding = 0, rgba32f) uniform restrict writeonly image2D out_position;
layout(binding = 1, rgba32f) uniform restrict writeonly image2D out_normal;
layout(binding = 2, r32ui) uniform restrict writeonly uimage2D out_triangle;

// harness/scene/camera.h's CameraFrame.
uniform vec3 camera_eye;
uniform vec3 camera_forward;
uniform vec3 camera_right;
uniform vec3 camera_up;
uniform float camera_tan_half_fov_y;
uniform float camera_aspect;

vec3 vertex_normal(uint vertex) {
  return vec3(scene_normals[3u * vertex], scene_normals[3u * vertex + 1u], scene_normals[3u * vertex + 2u]);
}

void main() {
  const ivec2 size = imageSize(out_position);
  const ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(pixel, size))) return;
  work_add(invocations, 1);
  // CameraFrame::ray_direction of image pixel (x, y), y = 0 the top row.
  const int y = size.y - 1 - pixel.y;
  const float nx = (float(pixel.x) + 0.5) / float(size.x) * 2.0 - 1.0;
  const float ny = 1.0 - (float(y) + 0.5) / float(size.y) * 2.0;
  const vec3 direction = normalize(camera_forward + camera_right * (nx * camera_tan_half_fov_y * camera_aspect) +
                                   camera_up * (ny * camera_tan_half_fov_y));
  trace_begin(camera_eye, direction, uintBitsToFloat(0x7f800000u));
#if RTAO_GPU_COUNT
  uint steps = 0u;
#endif
  for (;;) {
#if RTAO_GPU_COUNT
    ++steps;
#endif
    if (!trace_step(false)) break;
  }
  work_sample(nodes, trace_nodes);
  work_sample(triangles, trace_triangles);
#if RTAO_GPU_COUNT
  count_pixel[pixel.y * size.x + pixel.x] = uvec2(trace_nodes, trace_triangles);
  atomicMax(count_max_nodes, trace_nodes);
  atomicMax(count_max_triangles, trace_triangles);
  atomicMax(count_max_steps, steps);
#endif
  if (!trace_found) {  // background
    imageStore(out_position, pixel, vec4(0.0));
    imageStore(out_normal, pixel, vec4(0.0));
    imageStore(out_triangle, pixel, uvec4(0u));
    return;
  }
  const uint slot = trace_hit_slot;
  const uint triangle = bvh_triangles[3u * slot].w;
  const vec3 p0 = triangle_vertex(slot, 0u), p1 = triangle_vertex(slot, 1u), p2 = triangle_vertex(slot, 2u);
  const float u = trace_hit_uv.x, v = trace_hit_uv.y;
  const vec3 position = (1.0 - u - v) * p0 + u * p1 + v * p2;
  vec3 geometric = cross(p1 - p0, p2 - p0);
  geometric = normalize(dot(geometric, direction) > 0.0 ? -geometric : geometric);
  const vec3 n_raw = (1.0 - u - v) * vertex_normal(scene_indices[3u * triangle]) +
                     u * vertex_normal(scene_indices[3u * triangle + 1u]) +
                     v * vertex_normal(scene_indices[3u * triangle + 2u]);
  const float length_n = length(n_raw);
  vec3 n = length_n > 1e-12 ? n_raw / length_n : geometric;
  if (dot(n, camera_eye - position) < 0.0) n = -n;
  imageStore(out_position, pixel, vec4(position, 1.0));
  imageStore(out_normal, pixel, vec4(n, 0.0));
  imageStore(out_triangle, pixel, uvec4(triangle + 1u, 0u, 0u, 0u));
}
