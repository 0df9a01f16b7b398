#pragma once
// Indirect lighting with photon differentials traced through the LDM (thesis §5) as a
// measured pass: the camera G-buffer (with albedo), then PhotonLighting (light G-buffer,
// photon tracing through the structure's query API, splatting, direct light, sum). Its first
// image, `indirect`, is scored against the single-bounce Embree reference (what the method
// approximates) and, under the prefix multi_, against the multi-bounce one
// (harness/reference/lighting_reference.h).
//
// Parameters (--param indirect:KEY=VALUE, comma lists are run axes):
//   s                 footprint scale (> 0; 1: one light texel's beam), default 4
//   a                 topological bias (>= 0), default a = s
//   t_foot            footprint threshold, scene units (max norm of s * D x), default inf (off)
//   depth_threshold   camera depth test tolerance, scene units, default 3 LDM pixels
//   emission          thesis (secondaries weighted |cos| 2/N, default) or normalized
//                     (|cos| / their sum: exactly rho Phi1; docs/measured/indirect.md)
//   r_light           R_light, the light G-buffer's side, default 64
//   photon_capacity   fixes the photon buffer (photons) under every sizing policy
//   photon_budget_mib the photon buffer's budget under --sizing budget (default: the run's)
// and from the run's axes: trace, normal_offset_pixels (as the AO pass's).
#include <memory>

#include "harness/passes/gbuffer_pass.h"
#include "harness/passes/pass.h"
#include "harness/records/columns.h"
#include "harness/passes/photon_lighting.h"

namespace ldm {

// Pass's interface (LDM_PASS_DECLARATIONS) and what the pass adds: declarations alike in
// form in every pass's header, each its own.
class IndirectLighting : public Pass {
 public:
  explicit IndirectLighting(StructureParams& params);
  LDM_PASS_DECLARATIONS("indirect");
  // What its shaders count in the counting replay (harness/measure/work_counters.h).
  static std::vector<WorkCounter> work_counters();
  Image coverage() const override;
  std::string loss() const override;
  void continue_sizing_from(const Pass& measured) override;
  // The splats are blended additively in the order photon_tracing appended the photons,
  // which its atomics decide: float sums of up to thousands of splats per pixel in another
  // order differ by up to n * 2^-24 relative (1e-4 holds n <= ~1,600). Where the photon
  // buffer overflowed, which photons were stored is itself decided by arrival order, so no
  // tolerance holds: infinite (the record is lossy already, by loss()).
  double image_order_tolerance() const override;
  std::vector<std::string> problems() const override;
  // Stored photons whose footprint floats cannot resolve where they lie (photon_resolution).
  std::vector<std::string> warnings() const override;
  std::vector<BufferMemory> memory() const override;
  std::vector<ScoredReference> references(const Scene& scene, int width, int height,
                                          const ReferenceSettings& settings) const override;

  // The scene's settings (its AO trace settings) with this pass's parameters applied.
  IndirectSettings settings_for(const Scene& scene) const;
  const PhotonLighting& lighting() const { return *lighting_; }
  const GBufferPass& camera_gbuffer() const { return *gbuffer_; }

 private:
  IndirectSettings settings_;
  std::optional<float> normal_offset_pixels_;  // unset: the scene's
  const Scene* scene_ = nullptr;
  const GpuScene* gpu_scene_ = nullptr;
  const LdmStructure* structure_ = nullptr;
  std::unique_ptr<GBufferPass> gbuffer_;
  std::unique_ptr<PhotonLighting> lighting_;
};

}  // namespace ldm
