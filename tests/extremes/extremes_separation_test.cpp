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

constexpr uint32_t kSeparationResolution = 16;

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
  const test::LdmFixture probe(planes(1.0f), 1, kSeparationResolution);
  const double range = probe.views.views[0].depth_range;
  const float h = float(16.0 * ulp(range));
  ASSERT_GT(h, 2.0 * range / std::ldexp(1.0, 24));
  const test::LdmFixture fixture(planes(h), 1, kSeparationResolution);
  for (const auto& name : structure_names()) {
    const Separation s = measure(fixture, name);
    EXPECT_GT(s.pixels, kSeparationResolution * kSeparationResolution / 2) << name;
    EXPECT_EQ(s.distinct, s.pixels) << name << ": layers " << h << " apart merged";
  }
  if (!std::getenv("LDM_EXTREMES_SCAN")) return;
  // The scan: the smallest h = 2^-k (k = 8..30) at which every pixel still shows two layers.
  for (const auto& name : structure_names()) {
    double smallest = 0, quantum = 0, depth = 0;
    for (int k = 8; k <= 30; ++k) {
      const float hk = std::ldexp(1.0f, -k);
      const test::LdmFixture f(planes(hk), 1, kSeparationResolution);
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

namespace ldm {
namespace {

// Depths closer than one of the HA-buffer's 24-bit key steps collide on one key: the
// integrity check counts them (tied_depths), which the record then flags (issue 35); a
// structure that stores the float keeps them apart and counts none.
TEST(ExtremesSeparation, DepthsCollidedOnOneQuantisedKeyAreCounted) {
  // The two layers 1e-6 apart near one end of a depth range of ~20 (a small triangle 20
  // below them stretches it): floats there are ~1e-7 apart, the 24-bit key steps 1.9e-6 (measured: of 72
  // fragments the HA-buffer ties 36, PSPPSLL none).
  Scene scene = planes(1.0e-6f);
  for (const glm::vec3 far_point : {glm::vec3(0.0f, -20.0f, 0.0f), glm::vec3(0.01f, -20.0f, 0.0f),
                                  glm::vec3(0.0f, -20.0f, 0.01f)}) {
    scene.mesh.positions.push_back(far_point);
    scene.mesh.normals.push_back({0.0f, 1.0f, 0.0f});
  }
  const auto base = uint32_t(scene.mesh.positions.size() - 3);
  scene.mesh.triangles.emplace_back(base, base + 1, base + 2);
  scene.mesh.triangle_materials.push_back(scene.mesh.triangle_materials.front());
  const test::LdmFixture fixture(scene, 1, kSeparationResolution);
  for (const char* structure : {"psppsll", "habuffer"}) {
    const auto s = fixture.build(structure);
    const LdmIntegrity integrity = LdmInspector(*s, *fixture.inputs).check();
    std::printf("%s: %llu fragments, %llu tied, quantum %g\n", structure,
                (unsigned long long)integrity.fragments, (unsigned long long)integrity.tied_depths,
                s->depth_quantum(fixture.views.views[0]));
    if (s->depth_quantum(fixture.views.views[0]) > 0.0)
      EXPECT_GT(integrity.tied_depths, integrity.fragments / 4) << structure;
    else
      EXPECT_EQ(integrity.tied_depths, 0u) << structure;
  }
}

}  // namespace
}  // namespace ldm
