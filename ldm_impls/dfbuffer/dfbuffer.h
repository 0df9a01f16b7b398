#pragma once
// The dynamic fragment buffer (thesis §3.2.10, [Comba et al. 2012]): per-pixel variable-
// length arrays stored back to back, exactly sized. Two geometry passes: one counts the
// fragments of every pixel, a parallel prefix sum turns the counts into offsets, the second
// stores every fragment at offset + (--count), and a compute pass sorts every pixel's range.
// All views share one set of buffers (layout: shaders/ldm/dfbuffer/layout.glsl).
//
// Sub-passes: clear, count, prefix_sum, construct, sort.
// Sizing: the depth array's capacity follows the sizing policy (ldm_impls/common/sizing.h):
// oracle: the census's total; census: the count pass and scan are this structure's own
// census, so no separate census runs: build() reads the scan total back ("readback", a
// timed sync) and grows the depth array to it ("reallocate") before storing;
// previous_frame: the last build's scan total (needed()), rebuilt on overflow; budget: what
// the budget leaves after counts, offsets and scan scratch. stats() reads back the scan's
// total and flags a build whose total differs from the capacity ("storage_mismatch");
// fragments that find no slot are counted as lost.
// Parameters:
//   local=K   size of the sort's local array, 1..128 (default: under the oracle policy the
//             census's maximum depth complexity capped at 128, else 64); longer ranges are
//             heap-sorted in place in the depth array and counted as "lists_sorted_in_place".
#include <memory>

#include "harness/gl/gl_objects.h"
#include "ldm_impls/dfbuffer/prefix_sum.h"
#include "ldm_impls/ldm_structure.h"

namespace ldm {

class DfBuffer final : public LdmStructure {
 public:
  explicit DfBuffer(StructureParams& params);
  LDM_STRUCTURE_DECLARATIONS("dfbuffer");
  bool counts_own_fragments() const override { return true; }

 private:
  void clear(GpuTimer* timer);
  void count(const BuildInputs& in, GpuTimer* timer);
  void prefix_sum(GpuTimer* timer);
  void construct(const BuildInputs& in, GpuTimer* timer);
  void sort(GpuTimer* timer);
  void allocate_depths(uint64_t capacity);
  uint64_t read_scan_total() const;
  uint64_t count_unfilled_slots() const;

  SizingPlan plan_;
  uint32_t requested_local_ = 0;  // 0: from the policy
  uint32_t local_ = 0;            // K of the sort pass
  uint64_t pixels_ = 0;           // N * R_LDM^2
  uint64_t capacity_ = 0;         // depths, as the sizing policy chose
  ShaderDefines base_defines_, query_defines_;
  GlBuffer counts_, offsets_, depths_;
  // [0] lost: no slot left in the pixel's range, [1] lost: slot past the depth array,
  // [2] lists sorted in place, [3] unfilled slots (written by stats()).
  GlBuffer counters_;
  std::unique_ptr<PrefixSum> scan_;
  const FragmentSource* fragments_ = nullptr;  // from prepare(), for recompiles on resize
  GlProgram count_program_, build_program_, sort_program_, unfilled_program_;
};

}  // namespace ldm
