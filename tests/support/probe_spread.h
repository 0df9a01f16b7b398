#pragma once
// A run-to-run spread as one probe measured it, for the calibration tests (tests/timing): the
// probe's spread, pairs, processes, time, load (average and busy CPUs), build and processes' medians; the rest as
// RunToRunSpread's defaults.
#include "harness/measure/run_to_run_spread.h"

namespace ldm::test {

inline RunToRunSpread probe_spread(const ProbeEntry& probe) {
  return {.spread = probe.spread,
          .pairs = probe.pairs,
          .processes = probe.processes,
          .measured_at = probe.measured_at,
          .load_average = probe.load_average,
          .busy_cpus = probe.busy_cpus,
          .commit = probe.commit,
          .medians = probe.medians};
}

}  // namespace ldm::test
