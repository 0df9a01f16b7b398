// Rays through the BVH of harness/passes/gpu_bvh.h, one step at a time, for the GPU ray
// tracer's shaders (rtao_gpu_primary.comp, rtao_gpu.comp). A step tests one inner node (both
// children's boxes: the nearer child next, the other pushed), or one triangle of the current
// leaf, or pops the stack; trace_step() returns false when nothing is left to visit. The
// caller's loop calls it (the "if-if" traversal of Aila and Laine 2009): with every loop of a
// shader folded into one, a SIMD group runs exactly as many iterations as its longest
// invocation, which llvmpipe's loop limiter judges (harness/passes/trace_steps.h).
//
// Needs RTAO_GPU_STACK (the tree's depth), the bindings RTAO_GPU_NODES_BINDING,
// RTAO_GPU_TRIANGLES_BINDING, RTAO_GPU_SLOTS_BINDING, and RTAO_GPU_COUNT (1: count the nodes
// and triangles of the current ray in trace_nodes and trace_triangles; so does the shared
// counting replay's variant, WORK_COUNTING, whose callers work_sample them per ray).
#include "common/work_counters.glsl"
#define RTAO_GPU_COUNT_RAY (RTAO_GPU_COUNT || WORK_COUNTING)

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
// Per pixel: BVH nodes visited and triangles tested by its rays, summed; then the maxima over
// every ray (nodes, triangles) and over every invocation (loop iterations).
layout(std430, binding = RTAO_GPU_COUNTS_BINDING) restrict buffer RtaoGpuCounts {
  uint count_max_nodes;
  uint count_max_triangles;
  uint count_max_steps;
  uint count_pad;
  uvec2 count_pixel[];
};
#endif

const uint kNone = 0xffffffffu;  // gpu_bvh.h's kGpuBvhNoChild

vec3 triangle_vertex(uint slot, uint vertex) {
  return uintBitsToFloat(bvh_triangles[3u * slot + vertex].xyz);
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

// Möller-Trumbore (gpu_bvh.cpp's hit_triangle): the hit's t (negative on a miss) and its
// barycentrics of vertices 1 and 2 (Embree's u, v).
float hit_triangle(uint slot, vec3 origin, vec3 direction, out vec2 uv) {
  uv = vec2(0.0);
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
  uv = vec2(u, v);
  return dot(e2, q) * inverse;
}

// 1 / d, with components smaller than 1e-30 replaced by +-1e-30 (gpu_bvh.cpp's
// safe_inverse): no 0 * inf in the slab test.
vec3 safe_inverse(vec3 d) {
  const vec3 signs = vec3(greaterThanEqual(d, vec3(0.0))) * 2.0 - 1.0;
  return 1.0 / mix(d, signs * 1e-30, lessThan(abs(d), vec3(1e-30)));
}

// The ray being traced: its own private state (shader globals, one set per invocation).
vec3 trace_origin, trace_direction, trace_inverse;
float trace_t_max;   // the nearest hit so far, else the ray's end
bool trace_found;
uint trace_hit_slot;  // the nearest hit's triangle (its bvh_triangles slot) and barycentrics
vec2 trace_hit_uv;
uint trace_node, trace_leaf_next, trace_leaf_left;
uint trace_stack_word[RTAO_GPU_STACK], trace_stack_count[RTAO_GPU_STACK];
float trace_stack_enter[RTAO_GPU_STACK];
int trace_stack_size;
#if RTAO_GPU_COUNT_RAY
uint trace_nodes, trace_triangles;  // of the current ray
#endif

void trace_begin(vec3 origin, vec3 direction, float t_far) {
  trace_origin = origin;
  trace_direction = direction;
  trace_inverse = safe_inverse(direction);
  trace_t_max = t_far;
  trace_found = false;
  trace_hit_slot = 0u;
  trace_hit_uv = vec2(0.0);
  trace_node = 0u;  // the root
  trace_leaf_left = 0u;
  trace_stack_size = 0;
#if RTAO_GPU_COUNT_RAY
  trace_nodes = 0u;
  trace_triangles = 0u;
#endif
}

// One step of the current ray; false when nothing is left to visit (the ray is done). With
// `any_hit` the first hit ends the ray.
bool trace_step(bool any_hit) {
  if (trace_leaf_left > 0u) {  // one triangle of the current leaf
#if RTAO_GPU_COUNT_RAY
    ++trace_triangles;
#endif
    vec2 uv;
    const float t = hit_triangle(trace_leaf_next, trace_origin, trace_direction, uv);
    if (t > 0.0 && t < trace_t_max) {
      trace_t_max = t;
      trace_found = true;
      trace_hit_slot = trace_leaf_next;
      trace_hit_uv = uv;
      if (any_hit) {
        trace_leaf_left = 0u;
        trace_stack_size = 0;
        return true;
      }
    }
    ++trace_leaf_next;
    --trace_leaf_left;
    return true;
  }
  if (trace_node != kNone) {  // one inner node: both children's boxes
#if RTAO_GPU_COUNT_RAY
    ++trace_nodes;
#endif
    const uvec4 a = bvh_nodes[4u * trace_node], b = bvh_nodes[4u * trace_node + 1u],
                c = bvh_nodes[4u * trace_node + 2u], d = bvh_nodes[4u * trace_node + 3u];
    const uint word0 = a.w, word1 = b.w, count0 = c.w, count1 = d.w;
    float t0 = 0.0, t1 = 0.0;
    const bool hit0 = word0 != kNone && hit_box(uintBitsToFloat(a.xyz), uintBitsToFloat(b.xyz),
                                                 trace_origin, trace_inverse, trace_t_max, t0);
    const bool hit1 = word1 != kNone && hit_box(uintBitsToFloat(c.xyz), uintBitsToFloat(d.xyz),
                                                 trace_origin, trace_inverse, trace_t_max, t1);
    uint next_word = kNone, next_count = 0u;
    if (hit0 && hit1) {  // the nearer first, the other on the stack
      const bool first0 = t0 <= t1;
      trace_stack_word[trace_stack_size] = first0 ? word1 : word0;
      trace_stack_count[trace_stack_size] = first0 ? count1 : count0;
      trace_stack_enter[trace_stack_size] = first0 ? t1 : t0;
      ++trace_stack_size;
      next_word = first0 ? word0 : word1;
      next_count = first0 ? count0 : count1;
    } else if (hit0 || hit1) {
      next_word = hit0 ? word0 : word1;
      next_count = hit0 ? count0 : count1;
    }
    trace_node = kNone;
    if (next_word != kNone) {
      if (next_count > 0u) {
        trace_leaf_next = next_word;
        trace_leaf_left = next_count;
      } else {
        trace_node = next_word;
      }
    }
    return true;
  }
  if (trace_stack_size > 0) {
    --trace_stack_size;
    if (trace_stack_enter[trace_stack_size] <= trace_t_max) {  // else a nearer hit was found since
      if (trace_stack_count[trace_stack_size] > 0u) {
        trace_leaf_next = trace_stack_word[trace_stack_size];
        trace_leaf_left = trace_stack_count[trace_stack_size];
      } else {
        trace_node = trace_stack_word[trace_stack_size];
      }
    }
    return true;
  }
  return false;
}
