// Degenerate photon differentials (shaders/passes/indirect/photon_differential.glsl): every
// case the trace can meet is reported so that the pass culls and counts it.
#include <gtest/gtest.h>

#include <cmath>

#include "harness/gl/bindings.h"
#include "harness/gl/gl_objects.h"
#include "harness/gl/shader_program.h"
#include "support/test_support.h"

namespace ldm {
namespace {

struct ProbeResults {
  uint32_t ok[8];
  float values[8][4];
};

TEST(IndirectDegenerate, DifferentialFunctionsReportEveryDegenerateCase) {
  test::gl_context();
  const GlProgram probe = build_program(
      {{GL_COMPUTE_SHADER, "passes/indirect/photon_differential_probe.comp", {}}}, binding_defines());
  GlBuffer out("probe", sizeof(ProbeResults));
  out.clear_to_zero();
  out.bind_storage(kPassBinding0);
  probe.use();
  glDispatchCompute(1, 1, 1);
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  ProbeResults r{};
  out.download(&r, sizeof r);
  ASSERT_EQ(r.ok[7], 1u);  // the probe ran
  EXPECT_EQ(r.ok[0], 1u);
  EXPECT_NEAR(r.values[0][0], 0.02f * 0.02f, 1e-7f);  // the beam at t = 2: (0.01 * 2)^2
  EXPECT_EQ(r.ok[1], 0u) << "grazing transfer accepted";
  EXPECT_EQ(r.ok[2], 0u) << "nearly grazing transfer accepted";
  EXPECT_EQ(r.ok[3], 0u) << "infinite transfer accepted";
  EXPECT_EQ(r.ok[4], 0u) << "rotation between opposite directions accepted";
  EXPECT_EQ(r.ok[5], 1u);
  EXPECT_NEAR(r.values[5][0], r.values[5][1], 1e-6f);  // rotations keep lengths
  EXPECT_EQ(r.ok[6], 0u) << "collapsed footprint has area " << r.values[6][0];
  for (const auto& v : r.values)
    for (float x : v) EXPECT_TRUE(std::isfinite(x));
}

}  // namespace
}  // namespace ldm
