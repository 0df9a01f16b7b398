// Ray-traced ambient occlusion on the GPU (harness/passes/rtao_gpu.h): per pixel of the
// camera's G-buffer, RTAO_GPU_SPP cosine-weighted rays through the scene's BVH
// (harness/passes/gpu_bvh.h), with the reference's estimator (harness/reference/
// ao_estimator.h) in every detail that decides the image:
//  - x and the camera-facing shading normal are the G-buffer's (the reference's primary ray
//    finds the same point); the rays start kRayOffsetUlps float ulps of the largest
//    coordinate of x's triangle off the surface, along the triangle's plane normal on the
//    camera's side (harness/reference/surface_point.cpp);
//  - directions: Malley's method, z = sqrt(1 - u1), about the shading normal in Duff et al.'s
//    frame (harness/reference/hemisphere.h), u1 and u2 drawn in that order from the pixel's
//    PCG32 stream (pcg32.glsl: the CPU's numbers for the same seed and pass);
//  - visibility: attenuated, the closest hit within d_max, V = min(t / d_max, 1)^e (1 on a
//    miss); unattenuated, any hit at any distance, V = 0 (the first hit ends the ray);
//  - AO = the mean of V over the rays, 0 on background.
//
// The traversal is one loop (the "if-if" form of Aila and Laine 2009, with the pixel's rays
// in the same loop): each iteration tests one BVH node (both children's boxes), or one
// triangle of the current leaf, or finishes a ray and starts the next. llvmpipe counts every
// loop iteration of a SIMD group against one limit (harness/passes/trace_steps.h); with one
// loop a group runs exactly as many iterations as its longest invocation, which the counting
// variant (RTAO_GPU_COUNT 1, run untimed after the measured frames) records.
layout(local_size_x = 8, local_size_y = 8) in;

#include "passes/pcg32.glsl"

layout(binding = 0) uniform sampler2D gbuffer_position;
layout(binding = 1) uniform sampler2D gbuffer_normal;
layout(binding = 2) uniform usampler2D gbuffer_triangle;  // scene triangle + 1, 0: background
layout(binding = 0, r32f) uniform restrict writeonly image2D ao_image;

layout(std430, binding = RTAO_GPU_NODES_BINDING) restrict readonly buffer BvhNodes {
  // 4 per node (gpu_bvh.h). Read as words: the child words are small integers, whose bits as
  // floats would be denormals, which a device may flush.
  uvec4 bvh_nodes[];
};
layout(std430, binding = RTAO_GPU_TRIANGLES_BINDING) restrict readonly buffer BvhTriangles {
  uvec4 bvh_triangles[];  // 3 per triangle: v0 (w: scene index), v1, v2, as float bits
};
layout(std430, binding = RTAO_GPU_SLOTS_BINDING) restrict readonly buffer BvhSlots {
  uint bvh_slots[];  // per scene triangle: its index in bvh_triangles
};
#if RTAO_GPU_COUNT
// Per pixel: nodes visited and triangles tested by its rays, summed; then the maxima over
// every ray (nodes, triangles) and over every invocation (loop iterations).
layout(std430, binding = RTAO_GPU_COUNTS_BINDING) restrict buffer RtaoGpuCounts {
  uint count_max_nodes;
  uint count_max_triangles;
  uint count_max_steps;
  uint count_pad;
  uvec2 count_pixel[];
};
#endif

uniform vec3 camera_eye;
uniform uvec2 rng_seed_mixed;  // mix64(seed)
uniform uvec2 rng_pass_term;   // pass * 0xd1b54a32d192ed03 + 1
uniform float ao_d_max;
uniform float ao_falloff_exponent;
uniform float ray_offset_ulps;  // surface_point.h's kRayOffsetUlps

const uint kNone = 0xffffffffu;
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

// The slab test: where the ray enters the box within [0, t_max] (gpu_bvh.cpp's hit_box).
bool hit_box(vec3 lo, vec3 hi, vec3 origin, vec3 inverse, float t_max, out float t_enter) {
  const vec3 t0 = (lo - origin) * inverse, t1 = (hi - origin) * inverse;
  const vec3 near = min(t0, t1), far = max(t0, t1);
  t_enter = max(max(near.x, near.y), max(near.z, 0.0));
  // A few ulps of slack: a box touching the hit must not be culled by rounding.
  const float leave = min(min(far.x, far.y), min(far.z, t_max)) * 1.0000004;
  return t_enter <= leave;
}

// Möller-Trumbore (gpu_bvh.cpp's hit_triangle): the hit's t, negative on a miss.
vec3 triangle_vertex(uint slot, uint vertex) {
  return uintBitsToFloat(bvh_triangles[3u * slot + vertex].xyz);
}

float hit_triangle(uint slot, vec3 origin, vec3 direction) {
  const vec3 v0 = triangle_vertex(slot, 0u);
  const vec3 e1 = triangle_vertex(slot, 1u) - v0;
  const vec3 e2 = triangle_vertex(slot, 2u) - v0;
  const vec3 p = cross(direction, e2);
  const float det = dot(e1, p);
  if (det == 0.0) return -1.0;
  const float inverse = 1.0 / det;
  const vec3 s = origin - v0;
  const float u = dot(s, p) * inverse;
  if (u < 0.0 || u > 1.0) return -1.0;
  const vec3 q = cross(s, e1);
  const float v = dot(direction, q) * inverse;
  if (v < 0.0 || u + v > 1.0) return -1.0;
  return dot(e2, q) * inverse;
}

// 1 / d, with components smaller than 1e-30 replaced by +-1e-30 (gpu_bvh.cpp's
// safe_inverse): no 0 * inf in the slab test.
vec3 safe_inverse(vec3 d) {
  const vec3 signs = vec3(greaterThanEqual(d, vec3(0.0))) * 2.0 - 1.0;
  return 1.0 / mix(d, signs * 1e-30, lessThan(abs(d), vec3(1e-30)));
}

float visibility(bool found, float t) {
#if RTAO_GPU_ATTENUATED
  if (!found) return 1.0;
  const float ratio = min(t / ao_d_max, 1.0);
  return ao_falloff_exponent == 2.0 ? ratio * ratio : pow(ratio, ao_falloff_exponent);
#else
  return found ? 0.0 : 1.0;
#endif
}

void main() {
  const ivec2 size = imageSize(ao_image);
  const ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(pixel, size))) return;
  const vec4 position = texelFetch(gbuffer_position, pixel, 0);
  const uint triangle_id = texelFetch(gbuffer_triangle, pixel, 0).r;
  if (position.w == 0.0 || triangle_id == 0u) {  // background
    imageStore(ao_image, pixel, vec4(0.0));
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
#else
  const float t_far = uintBitsToFloat(0x7f800000u);  // +inf
#endif
  // Sums of V: per 64 rays in `partial`, then in `total`, so that thousands of rays lose no
  // digits to one float accumulator.
  float total = 0.0, partial = 0.0;
  uint rays_done = 0u;
  vec3 direction = vec3(0.0), inverse = vec3(0.0);
  float t_max = t_far;
  bool found = false;
  uint node = kNone, leaf_next = 0u, leaf_left = 0u;
  uint stack_word[RTAO_GPU_STACK], stack_count[RTAO_GPU_STACK];
  float stack_enter[RTAO_GPU_STACK];
  int stack_size = 0;
  bool ray_live = false;
#if RTAO_GPU_COUNT
  uint steps = 0u, ray_nodes = 0u, ray_triangles = 0u, pixel_nodes = 0u, pixel_triangles = 0u;
  uint max_nodes = 0u, max_triangles = 0u;
#endif
  for (;;) {
#if RTAO_GPU_COUNT
    ++steps;
#endif
    if (!ray_live) {
      if (rays_done > 0u) {  // finish the ray just traced
        partial += visibility(found, t_max);
        if ((rays_done & 63u) == 0u) {
          total += partial;
          partial = 0.0;
        }
#if RTAO_GPU_COUNT
        pixel_nodes += ray_nodes;
        pixel_triangles += ray_triangles;
        max_nodes = max(max_nodes, ray_nodes);
        max_triangles = max(max_triangles, ray_triangles);
        ray_nodes = 0u;
        ray_triangles = 0u;
#endif
      }
      if (rays_done == RTAO_GPU_SPP) break;
      const float u1 = pcg32_next_float(rng);
      const float u2 = pcg32_next_float(rng);
      direction = to_world(n, cosine_weighted_direction(u1, u2));
      inverse = safe_inverse(direction);
      t_max = t_far;
      found = false;
      node = 0u;  // the root
      stack_size = 0;
      ++rays_done;
      ray_live = true;
    }
    if (leaf_left > 0u) {  // one triangle of the current leaf
#if RTAO_GPU_COUNT
      ++ray_triangles;
#endif
      const float t = hit_triangle(leaf_next, origin, direction);
      ++leaf_next;
      --leaf_left;
      if (t > 0.0 && t < t_max) {
        t_max = t;
        found = true;
#if !RTAO_GPU_ATTENUATED
        leaf_left = 0u;  // any hit ends an unattenuated ray
        stack_size = 0;
#endif
      }
    } else if (node != kNone) {  // one inner node: both children's boxes
#if RTAO_GPU_COUNT
      ++ray_nodes;
#endif
      const uvec4 a = bvh_nodes[4u * node], b = bvh_nodes[4u * node + 1u],
                  c = bvh_nodes[4u * node + 2u], d = bvh_nodes[4u * node + 3u];
      const uint word0 = a.w, word1 = b.w, count0 = c.w, count1 = d.w;
      float t0 = 0.0, t1 = 0.0;  // kNone: no such child (gpu_bvh.h)
      const bool hit0 = word0 != kNone && hit_box(uintBitsToFloat(a.xyz), uintBitsToFloat(b.xyz), origin, inverse, t_max, t0);
      const bool hit1 = word1 != kNone && hit_box(uintBitsToFloat(c.xyz), uintBitsToFloat(d.xyz), origin, inverse, t_max, t1);
      uint next_word = kNone, next_count = 0u;
      if (hit0 && hit1) {  // the nearer first, the other on the stack
        const bool first0 = t0 <= t1;
        stack_word[stack_size] = first0 ? word1 : word0;
        stack_count[stack_size] = first0 ? count1 : count0;
        stack_enter[stack_size] = first0 ? t1 : t0;
        ++stack_size;
        next_word = first0 ? word0 : word1;
        next_count = first0 ? count0 : count1;
      } else if (hit0 || hit1) {
        next_word = hit0 ? word0 : word1;
        next_count = hit0 ? count0 : count1;
      }
      node = kNone;
      if (next_word != kNone) {
        if (next_count > 0u) {
          leaf_next = next_word;
          leaf_left = next_count;
        } else {
          node = next_word;
        }
      }
    } else if (stack_size > 0) {
      --stack_size;
      if (stack_enter[stack_size] <= t_max) {  // else a nearer hit was found since
        if (stack_count[stack_size] > 0u) {
          leaf_next = stack_word[stack_size];
          leaf_left = stack_count[stack_size];
        } else {
          node = stack_word[stack_size];
        }
      }
    } else {
      ray_live = false;  // nothing left to visit: the ray is done
    }
  }
  total += partial;
  imageStore(ao_image, pixel, vec4(total / float(RTAO_GPU_SPP)));
#if RTAO_GPU_COUNT
  count_pixel[pixel.y * size.x + pixel.x] = uvec2(pixel_nodes, pixel_triangles);
  atomicMax(count_max_nodes, max_nodes);
  atomicMax(count_max_triangles, max_triangles);
  atomicMax(count_max_steps, steps);
#endif
}
