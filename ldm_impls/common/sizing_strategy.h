#pragma once
// The sizing policies as strategy objects (ldm_impls/common/sizing.h says what each policy
// means). One strategy sizes every resizable GPU storage the same way: a structure's
// (ldm_impls/common/sizing_driver.h) and the indirect pass's photon buffer
// (harness/passes/photon_lighting.h). Each policy's behaviour lives in its strategy: the
// frame it runs, and the questions a structure asks when it plans its storage.
#include <cstdint>
#include <string>

#include "harness/measure/gpu_timer.h"
#include "ldm_impls/common/sizing.h"

namespace ldm {

// What a sizing strategy sizes and runs.
class SizedWork {
 public:
  virtual ~SizedWork() = default;
  // Whether the storage holds `needs`; a size fixed by a budget or a parameter always does.
  virtual bool fits(const SizingNeeds& needs) const = 0;
  // Grows the storage to hold `needs`.
  virtual void resize(const SizingNeeds& needs) = 0;
  // The work into the storage (a build, a photon trace), its own sub-passes timed by `timer`
  // (which may be null).
  virtual void run(GpuTimer* timer) = 0;
  // What the last run() needed, from its own GPU counters, even when it overflowed.
  virtual SizingNeeds needed() = 0;
  // A counting pass that stores nothing: what a run would need. Works whose run() counts
  // before it stores (the DF-buffer) have none and size themselves inside run().
  virtual bool has_census() const = 0;
  virtual SizingNeeds census() = 0;
  // Whether the storage has been sized for this scene (the photon buffer is not, before the
  // oracle's first frame; a structure is sized by its plan in prepare()).
  virtual bool sized() const { return true; }
};

// What the sizing cost over the frames so far.
struct SizingCounts {
  uint64_t rebuilds = 0;       // runs repeated after an overflow
  uint64_t reallocations = 0;  // times the storage grew
};

// A strategy's memory between frames (previous_frame's last needs).
struct SizingState {
  SizingNeeds last;
  bool have_last = false;
};

class SizingStrategy {
 public:
  virtual ~SizingStrategy() = default;
  virtual SizingPolicy policy() const = 0;
  const char* name() const { return sizing_policy_name(policy()); }

  // Questions a work asks when it plans its storage:
  // a budget fixes the storage; the work sizes itself within it and counts what does not fit;
  virtual bool fixed_by_budget() const { return false; }
  // sized exactly from the untimed census before the first frame (free; not a renderer's cost);
  virtual bool sized_by_oracle() const { return false; }
  // a timed census sizes every frame;
  virtual bool counts_every_frame() const { return false; }
  // grown from the last frame's own counters, an overflowing run rebuilt.
  virtual bool grows_from_counters() const { return false; }

  // One frame of `work` under the policy. Its sizing sub-passes are timed as `prefix` +
  // census, reallocate, readback and rebuild ("" for a structure, "photon_" for photons).
  virtual void frame(SizedWork& work, GpuTimer* timer, const std::string& prefix,
                     SizingState& state, SizingCounts& counts) const = 0;
};

// The strategy of a policy (a static object).
const SizingStrategy& sizing_strategy(SizingPolicy policy);

}  // namespace ldm
