#pragma once
// Pre-sorted per-pixel fixed-length arrays (thesis §3.2.7): every entry starts at the largest
// value; each fragment runs an insertion sort along its pixel's k entries with atomicMin,
// carrying the displaced (larger) value on, so the arrays are sorted when the geometry pass
// ends and no sort pass is needed. Layout and k policy: fixed_array_layout.h.
//
// Parameters:
//   k=0|n   entries per pixel; 0 (default): as the sizing policy says (fixed_array_layout.h;
//           lossless unless the policy is budget).
//           With a smaller k each pixel keeps its k nearest fragments; the values carried past
//           the k-th entry are dropped and counted exactly.
// Sub-passes: clear (entries to the empty value), construct (geometry pass).
#include <memory>

#include "harness/gl/gl_objects.h"
#include "ldm_impls/common/uint_reduction.h"
#include "ldm_impls/fixed_arrays/fixed_array_layout.h"
#include "ldm_impls/ldm_structure.h"

namespace ldm {

class Psppfla final : public LdmStructure {
 public:
  explicit Psppfla(StructureParams& params);
  LDM_STRUCTURE_DECLARATIONS("psppfla");

 private:
  void allocate(const FixedArrayLayout& layout);

  uint32_t requested_k_ = 0;
  FixedArrayLayout layout_;
  uint64_t pixels_ = 0;
  bool size_fixed_ = false;      // k from the parameter or the budget: never resized
  bool track_overflow_ = false;  // previous_frame: count drops per pixel
  ShaderDefines defines_;
  GlBuffer entries_, dropped_, overflow_;
  GlProgram build_program_;
  const FragmentSource* fragments_ = nullptr;  // from prepare(), for recompiles on resize
  std::unique_ptr<UintReduction> reduction_;
};

}  // namespace ldm
