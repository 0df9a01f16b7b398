#pragma once
// What the five AO passes (ao, hbao, gtao, rtao, rtao_gpu) share, written once: the d_max and
// visibility parameters each of them reads (ao_pass_parameter(AoAxis::DMax) and
// (AoAxis::Visibility)), and the scene's AO settings with them applied, which each pass
// describes, renders with and is scored against (ao_reference_for_run()).
#include "harness/passes/ao_parameters.h"
#include "harness/passes/pass.h"

namespace ldm {

class AoPassBase : public Pass {
 public:
  // An absent d_max and visibility=scene keep the scene's value (read_ao_overrides()).
  explicit AoPassBase(StructureParams& params) : overrides_(read_ao_overrides(params)) {}

  // The scene's AO settings with this pass's overrides applied.
  AoSettings settings_for(const Scene& scene) const { return apply_ao_overrides(scene.ao, overrides_); }

 protected:
  // The LDM AO adds its own (normal offset, trace, estimator) in its constructor.
  AoOverrides overrides_;
};

}  // namespace ldm
