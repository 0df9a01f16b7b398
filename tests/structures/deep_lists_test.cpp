// Post-sorting at depth complexity 1024 (the extremes sweep's stack1024, docs/measured/extremes.md):
// every structure that sorts after construction (PPSLL, PPFLA, the DF-buffer) must return
// the pixels' lists sorted, and PSPPSLL's, however long they are and whichever path (local
// array or in place) their sort takes. A tiny LDM keeps it fast: N = 1, R = 4, every pixel
// covered by all the layers.
#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>
#include <random>

#include "harness/scene/generators.h"
#include "structures/structure_test_support.h"

namespace ldm {
namespace {

constexpr uint32_t kLayers = 1024;

// kLayers copies of the plane scene's square, 1 / kLayers apart, drawn in a shuffled order
// so that the lists are built out of order (drawn bottom-up, a prepending list would come
// out sorted already and the sort would have nothing to do).
Scene shuffled_stack() {
  Scene scene = generate_scene("plane", {}, "test");
  const TriangleMesh square = scene.mesh;
  scene.mesh = {};
  std::vector<uint32_t> order(kLayers);
  std::iota(order.begin(), order.end(), 0u);
  std::shuffle(order.begin(), order.end(), std::mt19937(1024));
  for (uint32_t layer : order) {
    const auto base = uint32_t(scene.mesh.positions.size());
    for (size_t v = 0; v < square.positions.size(); ++v) {
      scene.mesh.positions.push_back(square.positions[v] +
                                     glm::vec3(0.0f, float(layer) / kLayers, 0.0f));
      scene.mesh.normals.push_back(square.normals[v]);
    }
    for (size_t t = 0; t < square.triangles.size(); ++t) {
      scene.mesh.triangles.push_back(square.triangles[t] + glm::uvec3(base));
      scene.mesh.triangle_materials.push_back(square.triangle_materials[t]);
    }
  }
  scene.validate();
  return scene;
}

TEST(DeepLists, PostSortedStructuresSortListsOfDepthComplexity1024) {
  const test::LdmFixture f(shuffled_stack(), 1, 4);
  ASSERT_EQ(f.census.max_depth_complexity, kLayers);
  const auto reference = test::build_psppsll_reference(f);
  for (const std::string name : {"ppsll", "ppfla", "dfbuffer"}) {
    const auto s = f.build(name);
    EXPECT_EQ(s->stats().fragments_lost, 0u) << name;
    const LdmIntegrity integrity = LdmInspector(*s, *f.inputs).check();
    EXPECT_EQ(integrity.fragments, f.census.total_fragments) << name;
    EXPECT_EQ(integrity.unsorted_pixels, 0u) << name;
    EXPECT_EQ(integrity.overlong_pixels, 0u) << name;
    if (name != "ppfla") {  // the list structures' local array is far shorter: in place
      const uint32_t local = uint32_t(std::stoul(test::sizing_value(*s, "sort_local")));
      ASSERT_LT(local, kLayers) << name;
      EXPECT_EQ(test::stats_counter(s->stats(), "lists_sorted_in_place"),
                double(test::pixels_longer_than(f.census, local)))
          << name;
    }
    test::expect_bit_identical_lists(reference.lists, test::read_all_views(*s, f), name);
  }
}

}  // namespace
}  // namespace ldm
