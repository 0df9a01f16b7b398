// Ray-traced ambient occlusion on the GPU (harness/passes/rtao_gpu.h): per pixel of the
// G-buffer (traced by rtao_gpu_primary.comp, or rasterised), RTAO_GPU_SPP cosine-weighted rays
// through the scene's BVH (harness/passes/gpu_bvh.h, bvh_traversal.glsl), with the
// reference's estimator (harness/reference/ao_estimator.h) in every detail that decides the
// image:
//  - x and the camera-facing shading normal are the G-buffer's; the rays start
//    kRayOffsetUlps float ulps of the largest coordinate of x's triangle off the surface,
//    along the triangle's plane normal on the camera's side (harness/reference/
//    surface_point.cpp);
//  - directions: Malley's method, z = sqrt(1 - u1), about the shading normal in Duff et al.'s
//    frame (harness/reference/hemisphere.h), u1 and u2 drawn in that order from the pixel's
//    PCG32 stream (pcg32.glsl: the CPU's numbers for the same seed and pass);
//  - visibility: attenuated, the closest hit within d_max, V = min(t / d_max, 1)^e (1 on a
//    miss); unattenuated, any hit at any distance, V = 0 (the first hit ends the ray);
//  - AO = the mean of V over the rays, 0 on background.
//
// The pixel's rays and their traversal are one loop: each iteration finishes a ray and starts
// the next, or takes one traversal step (bvh_traversal.glsl), so that the counting variant
// (RTAO_GPU_COUNT 1, run untimed after the measured frames) counts what llvmpipe's loop
// limiter counts.
layout(local_size_x = 8, local_size_y = 8) in;

#include "passes/pcg32.glsl"
#include "passes/bvh_traversal.glsl"

layout(binding = 0) uniform sampler2D gbuffer_position;
layout(binding = 1) uniform sampler2D gbuffer_normal;
layout(binding = 2) uniform usampler2D gbuffer_triangle;  // scene triangle + 1, 0: background
layout(binding = 0, r32f) uniform restrict writeonly image2D ao_image;

uniform vec3 camera_eye;
uniform uvec2 rng_seed_mixed;  // mix64(seed)
uniform uvec2 rng_pass_term;   // pass * 0xd1b54a32d192ed03 + 1
uniform float ao_d_max;
uniform float ao_falloff_exponent;
uniform float ray_offset_ulps;  // surface_point.h's kRayOffsetUlps

const float kFloatEpsilon = 1.1920928955078125e-7;  // FLT_EPSILON

// Duff et al. 2017, as NormalFrame (hemisphere.h), its copysign(1, n.z) included: the sign
// bit, so that n.z = -0 turns the frame as the CPU's does. (Any frame about n gives the same
// distribution; the same frame gives the CPU's very directions. The rasteriser's
// interpolation does not keep a mesh normal's -0, which Embree's does: where n.z is zero the
// frames, and so the directions, may differ from the CPU RTAO's for the same seed.)
vec3 to_world(vec3 n, vec3 local) {
  const float s = (floatBitsToUint(n.z) & 0x80000000u) != 0u ? -1.0 : 1.0;
  const float a = -1.0 / (s + n.z);
  const float b = n.x * n.y * a;
  const vec3 tangent = vec3(1.0 + s * n.x * n.x * a, s * b, -s * n.x);
  const vec3 bitangent = vec3(b, s + n.y * n.y * a, -n.y);
  return local.x * tangent + local.y * bitangent + local.z * n;
}

// Malley's method, as cosine_weighted_direction (hemisphere.h).
vec3 cosine_weighted_direction(float u1, float u2) {
  const float r = sqrt(u1);
  const float phi = 2.0 * 3.14159265358979 * u2;
  return vec3(r * cos(phi), r * sin(phi), sqrt(1.0 - u1));
}

// V of the ray just traced (the reference's attenuation).
float visibility(bool found, float t) {
#if RTAO_GPU_ATTENUATED
  if (!found) return 1.0;
  const float ratio = min(t / ao_d_max, 1.0);
  return ao_falloff_exponent == 2.0 ? ratio * ratio : pow(ratio, ao_falloff_exponent);
#else
  return found ? 0.0 : 1.0;
#endif
}

// One value per ray, tallied and added once per pixel (the sample sits in the traversal
// loop, whose every step a SIMD device runs it on, masked; work_counters.glsl).
WORK_SAMPLE_TALLY(rtao_nodes)
WORK_SAMPLE_TALLY(rtao_triangles)

void main() {
  const ivec2 size = imageSize(ao_image);
  const ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(pixel, size))) return;
  work_add(invocations, 1);
  const vec4 position = texelFetch(gbuffer_position, pixel, 0);
  const uint triangle_id = texelFetch(gbuffer_triangle, pixel, 0).r;
  if (position.w == 0.0 || triangle_id == 0u) {  // background
    imageStore(ao_image, pixel, vec4(0.0));
#if RTAO_GPU_COUNT
    count_pixel[pixel.y * size.x + pixel.x] = uvec2(0u);
#endif
    return;
  }
  const vec3 x = position.xyz;
  const vec3 n = texelFetch(gbuffer_normal, pixel, 0).xyz;
  // x's triangle: its plane's normal on the camera's side, and the offset of surface_point.
  const uint slot = bvh_slots[triangle_id - 1u];
  const vec3 p0 = triangle_vertex(slot, 0u), p1 = triangle_vertex(slot, 1u),
             p2 = triangle_vertex(slot, 2u);
  vec3 geometric = normalize(cross(p1 - p0, p2 - p0));
  if (dot(geometric, camera_eye - x) < 0.0) geometric = -geometric;
  const vec3 largest = max(abs(p0), max(abs(p1), abs(p2)));
  const float offset = ray_offset_ulps * kFloatEpsilon * max(largest.x, max(largest.y, largest.z));
  const vec3 origin = x + offset * geometric;

  // The reference's pixel index: image rows top first.
  const uint pixel_index = uint(size.y - 1 - pixel.y) * uint(size.x) + uint(pixel.x);
  Pcg32 rng = pixel_stream(rng_seed_mixed, rng_pass_term, pixel_index);

#if RTAO_GPU_ATTENUATED
  const float t_far = ao_d_max;
  const bool any_hit = false;
#else
  const float t_far = uintBitsToFloat(0x7f800000u);  // +inf
  const bool any_hit = true;
#endif
  // Sums of V: per 64 rays in `partial`, then in `total`, so that thousands of rays lose no
  // digits to one float accumulator.
  float total = 0.0, partial = 0.0;
  uint rays_done = 0u;
  bool ray_live = false;
#if RTAO_GPU_COUNT
  uint steps = 0u, pixel_nodes = 0u, pixel_triangles = 0u, max_nodes = 0u, max_triangles = 0u;
#endif
  for (;;) {
#if RTAO_GPU_COUNT
    ++steps;
#endif
    if (!ray_live) {
      if (rays_done > 0u) {  // finish the ray just traced
        partial += visibility(trace_found, trace_t_max);
        if ((rays_done & 63u) == 0u) {
          total += partial;
          partial = 0.0;
        }
        work_sample_tally(rtao_nodes, nodes, trace_nodes);
        work_sample_tally(rtao_triangles, triangles, trace_triangles);
#if RTAO_GPU_COUNT
        pixel_nodes += trace_nodes;
        pixel_triangles += trace_triangles;
        max_nodes = max(max_nodes, trace_nodes);
        max_triangles = max(max_triangles, trace_triangles);
#endif
      }
      if (rays_done == RTAO_GPU_SPP) break;
      const float u1 = pcg32_next_float(rng);
      const float u2 = pcg32_next_float(rng);
      trace_begin(origin, to_world(n, cosine_weighted_direction(u1, u2)), t_far);
      ++rays_done;
    }
    ray_live = trace_step(any_hit);
  }
  total += partial;
  work_add(rays, RTAO_GPU_SPP);
  work_sample_flush(nodes, rtao_nodes);
  work_sample_flush(triangles, rtao_triangles);
  imageStore(ao_image, pixel, vec4(total / float(RTAO_GPU_SPP)));
#if RTAO_GPU_COUNT
  count_pixel[pixel.y * size.x + pixel.x] = uvec2(pixel_nodes, pixel_triangles);
  atomicMax(count_max_nodes, max_nodes);
  atomicMax(count_max_triangles, max_triangles);
  atomicMax(count_max_steps, steps);
#endif
}
