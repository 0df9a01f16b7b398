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
  // The parameters --param psppfla:KEY=VALUE sets, declared (harness/axes/axis.h).
  static std::vector<AxisSpec> parameters();
  // What its build counts in the counting replay (harness/measure/work_counters.h).
  static std::vector<WorkCounter> work_counters();
  // What its query code counts in a pass's sub-pass (filled in by the caller).
  static std::vector<WorkCounter> query_work_counters();

  std::string name() const override { return "psppfla"; }
  void prepare(const BuildInputs& in) override;
  void build(const BuildInputs& in, GpuTimer* timer) override;
  BuildStats stats() const override;
  SizingNeeds needed() override;
  bool fits(const SizingNeeds& needs) const override;
  void resize(const SizingNeeds& needs) override;
  std::vector<std::string> query_sources() const override;
  ShaderDefines query_defines() const override;
  void bind_for_query() const override;
  std::vector<BufferMemory> memory() const override;
  std::vector<std::pair<std::string, std::string>> sizing() const override;

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
