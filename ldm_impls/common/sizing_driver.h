#pragma once
// Runs one structure's build under its sizing policy's strategy
// (ldm_impls/common/sizing_strategy.h), charging every step of sizing to the build's timed
// sub-passes:
//   oracle, budget   build()                                (sized in prepare())
//   census           "census" (count pass, GPU reduction, two words read back), then
//                    "reallocate" when the storage does not hold it, then build(); for a
//                    structure that counts its own fragments (the DF-buffer) just build(),
//                    which reads its scan total back itself
//   previous_frame   "reallocate" when the last frame's needs do not fit, build(),
//                    "readback" (the structure's own counters: what it needed), and when the
//                    build overflowed "rebuild" (resize to those needs and build again,
//                    timed as one sub-pass; counted)
// The frame loop calls build() where it would call the structure's build().
#include <cstdint>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "ldm_impls/common/fragment_census.h"
#include "ldm_impls/common/sizing_strategy.h"
#include "ldm_impls/ldm_structure.h"

namespace ldm {

class SizingDriver {
 public:
  // `structure` prepared with `in`; both outlive the driver.
  SizingDriver(LdmStructure& structure, const BuildInputs& in);
  ~SizingDriver();

  void build(GpuTimer* timer);
  // Takes the sizing state of `measured`, a driver of the same configuration, so that this
  // one's first frame is sized as `measured`'s next would be (previous_frame: grown to what
  // its last frame needed, no overflow to rebuild): the counting replay's single frame.
  void continue_from(const SizingDriver& measured) { state_ = measured.state_; }

  // Rebuilds after an overflow and reallocations, over every build so far.
  uint64_t rebuilds() const { return counts_.rebuilds; }
  uint64_t reallocations() const { return counts_.reallocations; }
  // Record fields (strings): policy, budget, first guess, the oracle's label.
  std::vector<std::pair<std::string, std::string>> describe() const;
  // Buffers the policy itself needs (the census pass's counts).
  std::vector<BufferMemory> memory() const;

 private:
  LdmStructure& structure_;
  const BuildInputs& in_;
  const SizingStrategy& strategy_;
  std::unique_ptr<CensusPass> census_;
  SizingState state_;
  SizingCounts counts_;
};

}  // namespace ldm
