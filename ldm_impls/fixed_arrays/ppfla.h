#pragma once
// Per-pixel fixed-length arrays (thesis §3.2.6, "Z^3 revisited"): a per-pixel atomic count
// hands each fragment the next of its pixel's k entries; a compute pass then sorts every
// pixel's entries. Layout and k policy: fixed_array_layout.h. Shaders: shaders/ldm/fixed_arrays/.
//
// Parameters:
//   k=0|n   entries per pixel; 0 (default): as the sizing policy says (fixed_array_layout.h;
//           lossless unless the policy is budget). Fragments past k are dropped (whichever
//           arrive last) and counted exactly.
// Sub-passes: clear (counts to 0), construct (geometry pass), sort (insertion sort per pixel).
#include <memory>

#include "harness/gl/gl_objects.h"
#include "ldm_impls/common/uint_reduction.h"
#include "ldm_impls/fixed_arrays/fixed_array_layout.h"
#include "ldm_impls/ldm_structure.h"

namespace ldm {

class Ppfla final : public LdmStructure {
 public:
  explicit Ppfla(StructureParams& params);
  LDM_STRUCTURE_DECLARATIONS("ppfla");

 private:
  void allocate(const FixedArrayLayout& layout);
  void bind_storage() const;
  void sort_every_pixel() const;

  uint32_t requested_k_ = 0;
  FixedArrayLayout layout_;
  uint64_t pixels_ = 0;
  bool size_fixed_ = false;  // k from the parameter or the budget: never resized
  ShaderDefines defines_;
  GlBuffer entries_, counts_, dropped_;
  GlProgram build_program_, sort_program_;
  const FragmentSource* fragments_ = nullptr;  // from prepare(), for recompiles on resize
  std::unique_ptr<UintReduction> reduction_;
};

}  // namespace ldm
