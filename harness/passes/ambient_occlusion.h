#pragma once
// Ambient occlusion (thesis §4.4) as a measured pass: the G-buffer from the scene's camera,
// then the AO trace through the structure's query API (AoPass), scored against the Embree
// AO reference (harness/reference/ao_reference.h).
//
// Parameters (each overrides the scene's "ao" settings):
//   d_max                  attenuation distance, scene units (> 0)
//   visibility             scene | attenuated | unattenuated
//   normal_offset_pixels   the §4.4.2 normal offset in LDM pixels (0 = off)
//   trace                  listing5 | interval | plane (harness/scene/ao_variants.h)
//   ao_estimator           eq13 | normalized
#include <memory>

#include "harness/passes/ao_pass.h"
#include "harness/passes/ao_pass_base.h"
#include "harness/passes/gbuffer_pass.h"
#include "harness/passes/pass.h"
#include "harness/records/columns.h"

namespace ldm {

// Pass's interface (LDM_PASS_DECLARATIONS) and what the pass adds: declarations alike in
// form in every pass's header, each its own.
class AmbientOcclusion : public AoPassBase {
 public:
  explicit AmbientOcclusion(StructureParams& params);
  LDM_PASS_DECLARATIONS("ao");
  // What its shaders count in the counting replay (harness/measure/work_counters.h).
  static std::vector<WorkCounter> work_counters();
  Image coverage() const override;
  std::vector<std::string> warnings() const override;
  std::vector<std::string> problems() const override;

 private:
  const Scene* scene_ = nullptr;
  const GpuScene* gpu_scene_ = nullptr;
  std::unique_ptr<GBufferPass> gbuffer_;
  std::unique_ptr<AoPass> ao_;
};

}  // namespace ldm
