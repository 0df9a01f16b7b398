// Extremes of layer separation (issue 12): two parallel squares h apart, face-on to the one
// view of N = 1. Every structure must keep both layers distinct once h is a few float ulps
// of their depth (the 32-bit HA-buffer: once h spans two of its depth steps). With
// LDM_EXTREMES_SCAN=1 the test also halves h down to where each structure merges the layers
// and prints the smallest separation it still resolves (scripts/extremes.sh).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>

#include "harness/scene/generators.h"
#include "support/ldm_fixture.h"

namespace ldm {
namespace {

constexpr uint32_t kResolution = 16;

Scene planes(float h) {
  Scene scene = generate_scene("parallel-planes", {{"h", 1.0}}, "test");
  for (glm::vec3& p : scene.mesh.positions)
    if (p.y > 0.0f) p.y = h;
  return scene;
}

struct Separation {
  uint32_t pixels = 0, distinct = 0;  // pixels with two layers; those with two distinct depths
  double max_depth = 0, quantum = 0;
};

Separation measure(const test::LdmFixture& fixture, const std::string& structure) {
  const auto s = fixture.build(structure);
  Separation result;
  result.quantum = s->depth_quantum(fixture.views.views[0]);
  const LdmInspector inspector(*s, *fixture.inputs);
  for (const auto& list : inspector.read_back(0)) {
    if (list.empty()) continue;
    result.max_depth = std::max(result.max_depth, double(list.back()));
    ++result.pixels;
    if (list.size() == 2 && list[1] > list[0]) ++result.distinct;
  }
  return result;
}

double ulp(double x) {
  const float f = float(x);
  return double(std::nextafter(f, std::numeric_limits<float>::infinity()) - f);
}

TEST(ExtremesSeparation, EveryStructureKeepsLayersAFewUlpsApart) {
  // 16 ulps of the depth of the planes (about half the view's depth range of ~11 units),
  // which is also more than two 24-bit HA-buffer steps (range / 2^24 each).
  const test::LdmFixture probe(planes(1.0f), 1, kResolution);
  const double range = probe.views.views[0].depth_range;
  const float h = float(16.0 * ulp(range));
  ASSERT_GT(h, 2.0 * range / std::ldexp(1.0, 24));
  const test::LdmFixture fixture(planes(h), 1, kResolution);
  for (const auto& name : structure_names()) {
    const Separation s = measure(fixture, name);
    EXPECT_GT(s.pixels, kResolution * kResolution / 2) << name;
    EXPECT_EQ(s.distinct, s.pixels) << name << ": layers " << h << " apart merged";
  }
  if (!std::getenv("LDM_EXTREMES_SCAN")) return;
  // The scan: the smallest h = 2^-k (k = 8..30) at which every pixel still shows two layers.
  for (const auto& name : structure_names()) {
    double smallest = 0, quantum = 0, depth = 0;
    for (int k = 8; k <= 30; ++k) {
      const float hk = std::ldexp(1.0f, -k);
      const test::LdmFixture f(planes(hk), 1, kResolution);
      const Separation s = measure(f, name);
      quantum = s.quantum;
      depth = s.max_depth;
      if (s.pixels == 0 || s.distinct < s.pixels) break;
      smallest = hk;
    }
    std::printf("separation %-9s smallest distinct h = %.3g (%.1f float ulps at depth %.2f; "
                "structure quantum %.3g)\n",
                name.c_str(), smallest, smallest / ulp(depth), depth, quantum);
  }
}

}  // namespace
}  // namespace ldm
