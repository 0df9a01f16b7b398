#include "harness/passes/gpu_bvh.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <string>

#include <embree3/rtcore.h>

#include "harness/util/error.h"

namespace ldm {
namespace {

// The builder's tree, in memory Embree's thread-local allocator owns (freed with the BVH).
struct BuildNode {
  bool leaf = false;
  // Inner node.
  BuildNode* children[2] = {nullptr, nullptr};
  RTCBounds bounds[2] = {};
  // Leaf: the scene triangles it holds.
  uint32_t count = 0;
  uint32_t* triangles = nullptr;
};

void* create_node(RTCThreadLocalAllocator alloc, unsigned int child_count, void*) {
  if (child_count > 2) return nullptr;  // maxBranchingFactor is 2
  return new (rtcThreadLocalAlloc(alloc, sizeof(BuildNode), 16)) BuildNode();
}

void set_children(void* node, void** children, unsigned int count, void*) {
  auto* n = static_cast<BuildNode*>(node);
  for (unsigned int i = 0; i < count; ++i) n->children[i] = static_cast<BuildNode*>(children[i]);
}

void set_bounds(void* node, const RTCBounds** bounds, unsigned int count, void*) {
  auto* n = static_cast<BuildNode*>(node);
  for (unsigned int i = 0; i < count; ++i) n->bounds[i] = *bounds[i];
}

void* create_leaf(RTCThreadLocalAllocator alloc, const RTCBuildPrimitive* primitives,
                  size_t count, void*) {
  auto* leaf = new (rtcThreadLocalAlloc(alloc, sizeof(BuildNode), 16)) BuildNode();
  leaf->leaf = true;
  leaf->count = uint32_t(count);
  leaf->triangles =
      static_cast<uint32_t*>(rtcThreadLocalAlloc(alloc, count * sizeof(uint32_t), 4));
  for (size_t i = 0; i < count; ++i) leaf->triangles[i] = primitives[i].primID;
  return leaf;
}

constexpr float kInf = std::numeric_limits<float>::infinity();

// Flattens the builder's tree depth first: an inner node's index is its position in
// `nodes`, a leaf's triangles are appended to `triangles` in visiting order.
class Flattener {
 public:
  Flattener(const TriangleMesh& mesh, GpuBvh& out) : mesh_(mesh), out_(out) {}

  // Emits `node` (an inner node) at the next index and returns it.
  uint32_t inner(const BuildNode& node, uint32_t level) {
    const auto index = uint32_t(out_.nodes.size());
    out_.depth = std::max(out_.depth, level);
    out_.nodes.emplace_back();
    uint32_t child[2] = {kGpuBvhNoChild, kGpuBvhNoChild}, count[2] = {0, 0};
    glm::vec3 lo[2] = {glm::vec3(0.0f), glm::vec3(0.0f)}, hi[2] = {glm::vec3(0.0f), glm::vec3(0.0f)};
    for (int c = 0; c < 2; ++c) {
      const BuildNode* n = node.children[c];
      if (!n) continue;  // a missing child: kGpuBvhNoChild
      lo[c] = {node.bounds[c].lower_x, node.bounds[c].lower_y, node.bounds[c].lower_z};
      hi[c] = {node.bounds[c].upper_x, node.bounds[c].upper_y, node.bounds[c].upper_z};
      if (n->leaf) {
        child[c] = leaf(*n);
        count[c] = n->count;
      } else {
        child[c] = inner(*n, level + 1);
      }
    }
    GpuBvhNode& out = out_.nodes[index];  // after the recursion: the vector may have grown
    out.min0 = lo[0];
    out.max0 = hi[0];
    out.min1 = lo[1];
    out.max1 = hi[1];
    out.child0 = child[0];
    out.child1 = child[1];
    out.count0 = count[0];
    out.count1 = count[1];
    return index;
  }

  uint32_t leaf(const BuildNode& node) {
    const auto first = uint32_t(out_.triangles.size());
    for (uint32_t i = 0; i < node.count; ++i) {
      const uint32_t t = node.triangles[i];
      const glm::uvec3 tri = mesh_.triangles[t];
      GpuBvhTriangle g;
      g.v0 = mesh_.positions[tri.x];
      g.v1 = mesh_.positions[tri.y];
      g.v2 = mesh_.positions[tri.z];
      g.scene_index = t;
      out_.triangles.push_back(g);
    }
    ++out_.leaves;
    out_.max_leaf_size = std::max(out_.max_leaf_size, node.count);
    return first;
  }

 private:
  const TriangleMesh& mesh_;
  GpuBvh& out_;
};

struct EmbreeDevice {
  RTCDevice device = rtcNewDevice(nullptr);
  ~EmbreeDevice() {
    if (device) rtcReleaseDevice(device);
  }
};

struct EmbreeBvh {
  RTCBVH bvh;
  explicit EmbreeBvh(RTCDevice device) : bvh(rtcNewBVH(device)) {}
  ~EmbreeBvh() {
    if (bvh) rtcReleaseBVH(bvh);
  }
};

}  // namespace

GpuBvhBounds gpu_bvh_bounds(uint64_t triangles) {
  return {std::max<uint64_t>(triangles, 1) * sizeof(GpuBvhNode),
          triangles * sizeof(GpuBvhTriangle), triangles * sizeof(uint32_t)};
}

std::string gpu_bvh_storage_refusal(uint64_t triangles, uint64_t block_bytes) {
  const GpuBvhBounds bounds = gpu_bvh_bounds(triangles);
  auto mib = [](uint64_t b) { return std::to_string((b + (1u << 20) - 1) >> 20) + " MiB"; };
  for (const auto& [buffer, bytes] : {std::pair{"bvh_nodes", bounds.node_bytes},
                                      std::pair{"bvh_triangles", bounds.triangle_bytes},
                                      std::pair{"bvh_slots", bounds.slot_bytes}})
    if (bytes > block_bytes)
      return "rtao_gpu: the BVH of this scene's " + std::to_string(triangles) +
             " triangles needs up to " + mib(bytes) + " in its storage block '" + buffer +
             "', more than this device's GL_MAX_SHADER_STORAGE_BLOCK_SIZE of " + mib(block_bytes) +
             "; the scene is too large for the GPU ray tracer on this device";
  return {};
}

GpuBvh build_gpu_bvh(const TriangleMesh& mesh) {
  if (mesh.triangles.empty()) throw UserError("rtao_gpu: the scene has no triangles to build a BVH of");
  const auto start = std::chrono::steady_clock::now();
  std::vector<RTCBuildPrimitive> primitives(mesh.triangles.size());
  for (size_t i = 0; i < mesh.triangles.size(); ++i) {
    const glm::uvec3 tri = mesh.triangles[i];
    const glm::vec3 a = mesh.positions[tri.x], b = mesh.positions[tri.y], c = mesh.positions[tri.z];
    const glm::vec3 lo = glm::min(a, glm::min(b, c)), hi = glm::max(a, glm::max(b, c));
    RTCBuildPrimitive& p = primitives[i];
    p.lower_x = lo.x;
    p.lower_y = lo.y;
    p.lower_z = lo.z;
    p.upper_x = hi.x;
    p.upper_y = hi.y;
    p.upper_z = hi.z;
    p.geomID = 0;
    p.primID = uint32_t(i);
  }
  EmbreeDevice device;
  if (!device.device) throw GpuError("Embree: rtcNewDevice failed");
  EmbreeBvh bvh(device.device);
  RTCBuildArguments args = rtcDefaultBuildArguments();
  args.buildQuality = RTC_BUILD_QUALITY_MEDIUM;  // binned SAH; no spatial splits
  args.maxBranchingFactor = 2;
  args.maxDepth = kGpuBvhMaxDepth;
  args.minLeafSize = 1;
  args.maxLeafSize = kGpuBvhMaxLeafSize;
  args.bvh = bvh.bvh;
  args.primitives = primitives.data();
  args.primitiveCount = primitives.size();
  args.primitiveArrayCapacity = primitives.size();
  args.createNode = create_node;
  args.setNodeChildren = set_children;
  args.setNodeBounds = set_bounds;
  args.createLeaf = create_leaf;
  const auto* root = static_cast<const BuildNode*>(rtcBuildBVH(&args));
  if (!root || rtcGetDeviceError(device.device) != RTC_ERROR_NONE)
    throw GpuError("Embree: rtcBuildBVH failed (error " +
                   std::to_string(rtcGetDeviceError(device.device)) + ")");

  GpuBvh out;
  out.nodes.reserve(mesh.triangles.size());
  out.triangles.reserve(mesh.triangles.size());
  Flattener flatten(mesh, out);
  if (root->leaf) {
    // A scene of a few triangles is one leaf: the shader starts at an inner node, so wrap it.
    BuildNode wrapper;
    wrapper.children[0] = const_cast<BuildNode*>(root);
    glm::vec3 lo(kInf), hi(-kInf);
    for (uint32_t i = 0; i < root->count; ++i) {
      const glm::uvec3 tri = mesh.triangles[root->triangles[i]];
      for (uint32_t v : {tri.x, tri.y, tri.z}) {
        lo = glm::min(lo, mesh.positions[v]);
        hi = glm::max(hi, mesh.positions[v]);
      }
    }
    wrapper.bounds[0] = {lo.x, lo.y, lo.z, 0.0f, hi.x, hi.y, hi.z, 0.0f};
    flatten.inner(wrapper, 1);
  } else {
    flatten.inner(*root, 1);
  }
  if (out.triangles.size() != mesh.triangles.size())
    throw GpuError("rtao_gpu: the BVH's leaves hold " + std::to_string(out.triangles.size()) +
                   " triangles, the scene " + std::to_string(mesh.triangles.size()));
  out.slots.assign(mesh.triangles.size(), std::numeric_limits<uint32_t>::max());
  for (uint32_t i = 0; i < out.triangles.size(); ++i) {
    uint32_t& slot = out.slots[out.triangles[i].scene_index];
    if (slot != std::numeric_limits<uint32_t>::max())
      throw GpuError("rtao_gpu: triangle " + std::to_string(out.triangles[i].scene_index) +
                     " is in two BVH leaves");
    slot = i;
  }
  out.build_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return out;
}

namespace {

// The slab test of the shader: where the ray enters the box within [0, t_far], or none.
bool hit_box(glm::vec3 lo, glm::vec3 hi, glm::vec3 origin, glm::vec3 inverse, float t_far,
             float* t_enter) {
  const glm::vec3 t0 = (lo - origin) * inverse, t1 = (hi - origin) * inverse;
  const glm::vec3 near = glm::min(t0, t1), far = glm::max(t0, t1);
  const float enter = std::max(std::max(near.x, near.y), std::max(near.z, 0.0f));
  // A few ulps of slack: a box touching the hit must not be culled by rounding.
  const float leave = std::min(std::min(far.x, far.y), std::min(far.z, t_far)) * 1.0000004f;
  *t_enter = enter;
  return enter <= leave;
}

// Möller-Trumbore, as the shader: the hit's t, or a negative value on a miss.
float hit_triangle(const GpuBvhTriangle& tri, glm::vec3 origin, glm::vec3 direction) {
  const glm::vec3 e1 = tri.v1 - tri.v0, e2 = tri.v2 - tri.v0;
  const glm::vec3 p = glm::cross(direction, e2);
  const float det = glm::dot(e1, p);
  if (det == 0.0f) return -1.0f;
  const float inverse = 1.0f / det;
  const glm::vec3 s = origin - tri.v0;
  const float u = glm::dot(s, p) * inverse;
  if (u < 0.0f || u > 1.0f) return -1.0f;
  const glm::vec3 q = glm::cross(s, e1);
  const float v = glm::dot(direction, q) * inverse;
  if (v < 0.0f || u + v > 1.0f) return -1.0f;
  return glm::dot(e2, q) * inverse;
}

glm::vec3 safe_inverse(glm::vec3 d) {
  glm::vec3 r;
  for (int i = 0; i < 3; ++i)
    r[i] = 1.0f / (std::abs(d[i]) < 1e-30f ? std::copysign(1e-30f, d[i]) : d[i]);
  return r;
}

}  // namespace

bool trace_gpu_bvh(const GpuBvh& bvh, glm::vec3 origin, glm::vec3 direction, float t_far,
                   bool any_hit, GpuBvhHit* hit) {
  struct Entry {
    uint32_t word, count;
    float t_enter;
  };
  std::vector<Entry> stack;
  const glm::vec3 inverse = safe_inverse(direction);
  float t_max = t_far;
  bool found = false;
  GpuBvhHit h;
  Entry next{0, 0, 0.0f};  // the root, an inner node
  bool have_next = true;
  for (;;) {
    if (!have_next) {
      if (stack.empty()) break;
      next = stack.back();
      stack.pop_back();
      if (next.t_enter > t_max) continue;  // a nearer hit was found since it was pushed
    }
    have_next = false;
    if (next.count > 0) {  // a leaf
      for (uint32_t i = 0; i < next.count; ++i) {
        ++h.triangles_tested;
        const GpuBvhTriangle& tri = bvh.triangles[next.word + i];
        const float t = hit_triangle(tri, origin, direction);
        if (t > 0.0f && t < t_max) {
          t_max = t;
          found = true;
          h.t = t;
          h.scene_triangle = tri.scene_index;
          if (any_hit) {
            *hit = h;
            return true;
          }
        }
      }
      continue;
    }
    ++h.nodes_visited;
    const GpuBvhNode& n = bvh.nodes[next.word];
    float t0 = 0, t1 = 0;
    const bool hit0 = n.child0 != kGpuBvhNoChild && hit_box(n.min0, n.max0, origin, inverse, t_max, &t0);
    const bool hit1 = n.child1 != kGpuBvhNoChild && hit_box(n.min1, n.max1, origin, inverse, t_max, &t1);
    const Entry c0{n.child0, n.count0, t0}, c1{n.child1, n.count1, t1};
    if (hit0 && hit1) {
      const bool first0 = t0 <= t1;
      stack.push_back(first0 ? c1 : c0);
      next = first0 ? c0 : c1;
      have_next = true;
    } else if (hit0 || hit1) {
      next = hit0 ? c0 : c1;
      have_next = true;
    }
  }
  *hit = h;
  return found;
}

}  // namespace ldm
