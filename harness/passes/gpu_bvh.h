#pragma once
// A bounding-volume hierarchy for tracing rays in a shader (shaders/passes/rtao_gpu.comp),
// built once on the CPU by Embree 3's builder API (rtcBuildBVH: Embree's binned SAH builder,
// our own node layout through its callbacks) and flattened into arrays a GLSL storage buffer
// holds as they are:
//  - nodes: a binary tree, 64 bytes a node, the bounds of both children in the parent (one
//    node read tests both children's boxes); node 0 is the root. Per child c in {0, 1}:
//      box_min[c], box_max[c]   its bounds
//      child[c], count[c]       count 0: an inner node's index (kGpuBvhNoChild: none, the
//                               second child of a root that is one leaf); else a leaf:
//                               `count` triangles from triangles[child[c]] on
//    laid out as four vec4: (min0, child0) (max0, child1) (min1, count0) (max1, count1),
//    the words as float bits;
//  - triangles: the scene's triangles in leaf order, 48 bytes each, vec4 v0 (w: the scene's
//    triangle index, as float bits), vec4 v1, vec4 v2;
//  - slots: per scene triangle, its index in `triangles` (the G-buffer names scene triangles).
// MEDIUM build quality (no spatial splits): every triangle is in exactly one leaf.
#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "harness/scene/scene.h"

namespace ldm {

struct GpuBvhNode {
  glm::vec3 min0;
  uint32_t child0;
  glm::vec3 max0;
  uint32_t child1;
  glm::vec3 min1;
  uint32_t count0;
  glm::vec3 max1;
  uint32_t count1;
};
static_assert(sizeof(GpuBvhNode) == 64, "four vec4 in GLSL");

struct GpuBvhTriangle {
  glm::vec3 v0;
  uint32_t scene_index;
  glm::vec3 v1;
  float pad1 = 0;
  glm::vec3 v2;
  float pad2 = 0;
};
static_assert(sizeof(GpuBvhTriangle) == 48, "three vec4 in GLSL");

// Embree's builder settings (RTCBuildArguments): a binary tree, leaves of at most
// kGpuBvhMaxLeafSize triangles, at most kGpuBvhMaxDepth levels (the shader's traversal
// stack is sized from the built tree's depth).
inline constexpr uint32_t kGpuBvhMaxLeafSize = 4;
inline constexpr uint32_t kGpuBvhMaxDepth = 48;
// The child word of a missing child (the shader skips it without testing its box).
inline constexpr uint32_t kGpuBvhNoChild = 0xffffffffu;

struct GpuBvh {
  std::vector<GpuBvhNode> nodes;
  std::vector<GpuBvhTriangle> triangles;
  std::vector<uint32_t> slots;
  uint32_t leaves = 0;
  uint32_t depth = 0;          // levels of inner nodes on the longest root-to-leaf path
  uint32_t max_leaf_size = 0;  // triangles in the largest leaf
  double build_ms = 0;         // CPU wall time: primitives, Embree's build, flattening

  uint64_t node_bytes() const { return nodes.size() * sizeof(GpuBvhNode); }
  uint64_t triangle_bytes() const { return triangles.size() * sizeof(GpuBvhTriangle); }
  uint64_t slot_bytes() const { return slots.size() * sizeof(uint32_t); }
  uint64_t bytes() const { return node_bytes() + triangle_bytes() + slot_bytes(); }
};

// The most bytes each of the BVH's arrays can take for `triangles` triangles (a binary tree
// over leaves of at least one triangle has fewer inner nodes than triangles): what to check
// against the device's storage block before building.
struct GpuBvhBounds {
  uint64_t node_bytes, triangle_bytes, slot_bytes;
};
GpuBvhBounds gpu_bvh_bounds(uint64_t triangles);
// Why a device whose storage blocks hold `block_bytes` (GL_MAX_SHADER_STORAGE_BLOCK_SIZE)
// cannot hold the BVH of `triangles` triangles, naming the array; "" when it can.
std::string gpu_bvh_storage_refusal(uint64_t triangles, uint64_t block_bytes);

// Builds the BVH of `mesh` in its own coordinates. Throws UserError for a mesh without
// triangles and GpuError when Embree fails.
GpuBvh build_gpu_bvh(const TriangleMesh& mesh);

// The closest hit of a ray in [t_near, t_far] by walking the flattened arrays exactly as the
// shader does (its stack order, its box and triangle tests): the tests' oracle for the layout,
// and a check that the flattening kept every triangle reachable. Returns false on a miss;
// `hit`'s counts are filled either way.
struct GpuBvhHit {
  float t = 0;
  uint32_t scene_triangle = 0;
  uint32_t nodes_visited = 0, triangles_tested = 0;
};
bool trace_gpu_bvh(const GpuBvh& bvh, glm::vec3 origin, glm::vec3 direction, float t_far,
                   bool any_hit, GpuBvhHit* hit);

}  // namespace ldm
