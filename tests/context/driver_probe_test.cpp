// The driver self-tests (harness/gl/driver_probe.h) and the defect they were written for,
// reduced to its few lines: a memory barrier inside a loop that the SIMD vectors of one work
// group leave at different iterations (shaders/probes/barrier_in_divergent_loop.glsl).
#include <gtest/gtest.h>

#include <iostream>

#include "harness/gl/driver_probe.h"
#include "support/test_support.h"

namespace ldm {
namespace {

// The probe can fail: its shader, made to skip an eighth of its invocations as a defective
// driver would, must be reported as losing at least those, in every stage and barrier.
TEST(DriverProbe, CatchesInvocationsThatNeverFinish) {
  test::gl_context();
  for (ProbeStage stage : {ProbeStage::Compute, ProbeStage::Fragment})
    for (ProbeBarrier barrier : {ProbeBarrier::MemoryBarrier, ProbeBarrier::MemoryBarrierBuffer}) {
      const BarrierProbeResult r = probe_barrier_in_divergent_loop(stage, barrier, true);
      EXPECT_FALSE(r.conformant()) << r.describe();
      EXPECT_LE(r.completed, r.invocations - r.invocations / 8) << r.describe();
      EXPECT_GT(r.invocations, 0u);
    }
}

// Every stage and barrier probed once; the record's text names exactly the failed ones.
TEST(DriverProbe, ConformanceCoversEveryStageAndBarrierAndNamesWhatFailed) {
  const DeviceInfo& device = test::gl_context().device();
  const DriverConformance& driver = driver_conformance();
  ASSERT_EQ(driver.barrier_probes.size(), 4u);
  size_t failed = 0;
  for (const BarrierProbeResult& probe : driver.barrier_probes) {
    std::cout << device.gl_renderer << ": " << probe.describe() << "\n";
    EXPECT_EQ(driver.barrier_defect(probe.stage, probe.barrier) != nullptr, !probe.conformant());
    if (!probe.conformant()) {
      ++failed;
      EXPECT_NE(driver.defects_text().find(probe.describe()), std::string::npos);
    }
  }
  if (failed == 0) EXPECT_EQ(driver.defects_text(), "none");
  EXPECT_EQ(device.driver_defects, driver.defects_text());
  EXPECT_EQ(&driver, &driver_conformance()) << "probed once per driver and process";
}

// The defect itself, as a reproducer to report upstream: on a conforming driver every
// invocation finishes. Mesa 22.3.6's lavapipe under zink loses 56 of 64 here, which is why
// PSPPSLL's insertion uses memoryBarrier() (docs/reference/structures.md#driver-conformance);
// scripts/zink-tests.sh runs it there and prints the outcome without failing CI on it.
TEST(DriverDefects, MemoryBarrierBufferInADivergentComputeLoopLosesNoInvocation) {
  test::gl_context();
  const BarrierProbeResult r =
      probe_barrier_in_divergent_loop(ProbeStage::Compute, ProbeBarrier::MemoryBarrierBuffer);
  EXPECT_TRUE(r.conformant()) << r.describe() << " on " << test::gl_context().device().gl_renderer
                              << ", " << test::gl_context().device().gl_version;
}

}  // namespace
}  // namespace ldm
