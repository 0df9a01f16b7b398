// The BVH the GPU ray tracer walks (harness/passes/gpu_bvh.h), without a GPU: its layout is
// whole (every triangle in one leaf, every box holding its subtree) and a walk of it finds
// the closest hits Embree's own BVH finds.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>

#include "harness/passes/gpu_bvh.h"
#include "harness/reference/embree_scene.h"
#include "harness/reference/pcg32.h"
#include "harness/scene/scene_loader.h"
#include "harness/util/error.h"

namespace ldm {
namespace {

bool contains(glm::vec3 lo, glm::vec3 hi, glm::vec3 p) {
  return glm::all(glm::lessThanEqual(lo, p)) && glm::all(glm::lessThanEqual(p, hi));
}

// Every triangle under child `c` of node `index` lies in the child's box; returns how many
// triangles the subtree holds.
uint64_t check_subtree(const GpuBvh& bvh, uint32_t word, uint32_t count, glm::vec3 lo, glm::vec3 hi) {
  if (count > 0) {
    for (uint32_t i = 0; i < count; ++i) {
      const GpuBvhTriangle& t = bvh.triangles.at(word + i);
      for (glm::vec3 v : {t.v0, t.v1, t.v2}) EXPECT_TRUE(contains(lo, hi, v)) << "triangle " << t.scene_index;
    }
    return count;
  }
  const GpuBvhNode& n = bvh.nodes.at(word);
  uint64_t total = 0;
  EXPECT_NE(n.child0, kGpuBvhNoChild) << "the first child always exists";
  // A child's box lies in its parent's box, and holds the child's triangles.
  for (glm::vec3 p : {n.min0, n.max0}) EXPECT_TRUE(contains(lo, hi, p));
  total += check_subtree(bvh, n.child0, n.count0, n.min0, n.max0);
  if (n.child1 != kGpuBvhNoChild) {
    for (glm::vec3 p : {n.min1, n.max1}) EXPECT_TRUE(contains(lo, hi, p));
    total += check_subtree(bvh, n.child1, n.count1, n.min1, n.max1);
  }
  return total;
}

void check_layout(const Scene& scene) {
  const GpuBvh bvh = build_gpu_bvh(scene.mesh);
  ASSERT_EQ(bvh.triangles.size(), scene.mesh.triangles.size());
  ASSERT_EQ(bvh.slots.size(), scene.mesh.triangles.size());
  for (uint32_t t = 0; t < bvh.slots.size(); ++t) ASSERT_EQ(bvh.triangles.at(bvh.slots[t]).scene_index, t);
  const glm::vec3 inf(std::numeric_limits<float>::infinity());
  EXPECT_EQ(check_subtree(bvh, 0, 0, -inf, inf), scene.mesh.triangles.size()) << scene.name;
  EXPECT_LE(bvh.depth, kGpuBvhMaxDepth);
  EXPECT_LE(bvh.max_leaf_size, kGpuBvhMaxLeafSize);
  EXPECT_LT(bvh.nodes.size(), std::max<size_t>(scene.mesh.triangles.size(), 2));
  EXPECT_EQ(bvh.bytes(), bvh.nodes.size() * 64 + bvh.triangles.size() * 52);
  const GpuBvhBounds bounds = gpu_bvh_bounds(scene.mesh.triangles.size());
  EXPECT_LE(bvh.node_bytes(), bounds.node_bytes);
  EXPECT_EQ(bvh.triangle_bytes(), bounds.triangle_bytes);
}

TEST(GpuBvh, LayoutHoldsEveryTriangleInsideItsBoxes) {
  for (const char* name : {"plane", "parallel-planes", "cornell", "atrium"}) check_layout(load_scene(name));
}

// Random rays from points inside the scene's bounds, closest hit (the attenuated AO's query)
// and any hit (the unattenuated one), against Embree's own BVH of the same triangles.
TEST(GpuBvh, WalkFindsEmbreesClosestHits) {
  for (const char* name : {"cornell", "atrium"}) {
    const Scene scene = load_scene(name);
    const GpuBvh bvh = build_gpu_bvh(scene.mesh);
    const EmbreeScene embree(scene);
    const BoundingSphere sphere = scene.bounding_sphere();
    Pcg32 rng(7, 1);
    int hits = 0, misses = 0;
    for (int i = 0; i < 4000; ++i) {
      const glm::vec3 origin = sphere.centre + 0.8f * sphere.radius *
                                                   (glm::vec3(rng.next_float(), rng.next_float(), rng.next_float()) * 2.0f - 1.0f);
      const float z = rng.next_float() * 2.0f - 1.0f, phi = 6.2831853f * rng.next_float();
      const float r = std::sqrt(1.0f - z * z);
      const glm::vec3 direction(r * std::cos(phi), r * std::sin(phi), z);
      const float t_far = i % 2 ? std::numeric_limits<float>::infinity() : 0.3f * sphere.radius;
      const auto expected = embree.intersect(origin, direction, 0.0f, t_far);
      GpuBvhHit hit;
      const bool found = trace_gpu_bvh(bvh, origin, direction, t_far, false, &hit);
      ASSERT_EQ(found, expected.has_value()) << name << " ray " << i;
      GpuBvhHit any;
      EXPECT_EQ(trace_gpu_bvh(bvh, origin, direction, t_far, true, &any), found);
      EXPECT_LE(any.triangles_tested, hit.triangles_tested);
      if (!found) {
        ++misses;
        continue;
      }
      ++hits;
      // The same surface at the same distance (two coplanar triangles may share a hit).
      EXPECT_NEAR(hit.t, expected->t, 1e-5f * std::max(1.0f, expected->t)) << name << " ray " << i;
      EXPECT_GE(hit.nodes_visited, 1u);
      EXPECT_GE(hit.triangles_tested, 1u);
    }
    EXPECT_GT(hits, 400) << name;
    EXPECT_GT(misses, 40) << name;
  }
}

TEST(GpuBvh, RefusesAnEmptyMesh) {
  EXPECT_THROW(build_gpu_bvh(TriangleMesh{}), UserError);
}

}  // namespace
}  // namespace ldm
