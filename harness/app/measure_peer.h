#pragma once
// measure() for a pass that reads no LDM structure (a screen-space or ray-traced peer such
// as HBAO): the scene uploaded with the attributes the pass asks for, then frames of the
// pass alone, every sub-pass timed. No census, views, baselines or build: the record's
// structure is "none" and its "frame" time is the pass's whole cost. A pass that runs on the
// CPU (PassRequirements::runs_on_cpu, rtao) is timed by the CPU's wall clock and its record's
// device is the CPU model.
#include <memory>
#include <string>

#include "harness/app/measurement.h"

namespace ldm {

// "CPU: <model name>" from /proc/cpuinfo (the device column of a CPU pass's record).
std::string cpu_model_name();

Measurement measure_peer(const Scene& scene, const MeasurementRequest& request,
                         std::unique_ptr<Pass> pass);

}  // namespace ldm
