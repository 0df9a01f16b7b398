#pragma once
// Driver self-tests: short GPU checks of behaviour the structures depend on and that a driver
// has been seen to get wrong (docs/reference/structures.md#driver-conformance). Each runs in
// milliseconds in the current context; the results are kept per driver (renderer and version)
// for the process, printed by `ldmbench info` and recorded in every record (driver_defects).
//
// The one probed today: a memory barrier inside a loop whose invocations leave it at different
// iterations. Mesa 22.3's lavapipe (under zink) runs memoryBarrierBuffer() and the other
// memory barriers but memoryBarrier() as a work-group execution barrier in compute shaders: a
// SIMD vector that passes the barrier more often than another of its work group waits there
// for good, and its invocations end without a trace (PSPPSLL's insertion loop lost 1,500 of
// 3,500 fragments in the contention test).
#include <cstdint>
#include <string>
#include <vector>

namespace ldm {

enum class ProbeStage { Compute, Fragment };
enum class ProbeBarrier { MemoryBarrier, MemoryBarrierBuffer };

const char* probe_stage_name(ProbeStage stage);
const char* probe_barrier_name(ProbeBarrier barrier);  // the GLSL call, e.g. "memoryBarrier()"

// One run of shaders/probes/barrier_in_divergent_loop.*: how many invocations finished.
struct BarrierProbeResult {
  ProbeStage stage = ProbeStage::Compute;
  ProbeBarrier barrier = ProbeBarrier::MemoryBarrier;
  uint32_t invocations = 0;
  uint32_t completed = 0;
  bool conformant() const { return completed == invocations; }
  // "memoryBarrierBuffer() in a divergent compute loop: 56 of 64 invocations lost"
  std::string describe() const;
};

// Runs the probe once in the current context. `drop_some` makes the probe's own shader skip
// an eighth of its invocations, as a defective driver would: its check must then fail.
BarrierProbeResult probe_barrier_in_divergent_loop(ProbeStage stage, ProbeBarrier barrier,
                                                   bool drop_some = false);

struct DriverConformance {
  std::vector<BarrierProbeResult> barrier_probes;  // every stage x barrier
  // Null when the probe of `barrier` in `stage` passed; else that probe.
  const BarrierProbeResult* barrier_defect(ProbeStage stage, ProbeBarrier barrier) const;
  // "none", or each failed probe's describe(), "; "-separated (the driver_defects column).
  std::string defects_text() const;
};

// Every probe, run on first use for the current context's driver (GL_RENDERER and
// GL_VERSION) and kept for the process.
const DriverConformance& driver_conformance();

}  // namespace ldm
