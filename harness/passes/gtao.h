#pragma once
// Ground-truth ambient occlusion (GTAO: Jimenez, Wu, Pesce and Jarabo 2016, "Practical
// Real-Time Strategies for Accurate Indirect Occlusion") as a measured peer of the LDM AO: the
// screen-space method engines ship today. It reads no LDM, only the camera's G-buffer
// (shaders/passes/gtao.frag: slices through the view vector, a horizon search on each side,
// the cosine-weighted integral in closed form), and is scored against the same Embree AO
// reference. The reference's attenuation weighs each rise of the horizon by 1 - V(r) at the
// distance of the sample that raised it (exact, in the limit of many steps, where the depth
// buffer holds what the rays hit: see the shader); docs/reference/passes.md says where it
// cannot apply.
//
// Parameters (--param gtao:KEY=VALUE, comma lists are run axes; d_max and visibility also from
// --d-max / --visibility):
//   slices       slice planes per pixel (1..64)
//   steps        samples per side of a slice (1..128)
//   radius       the search radius R as a multiple of d_max (0.05..8)
//   falloff      fraction of R over which an occluder's weight fades to 0 at R (0..1; 0: none)
//   thickness    beta of the paper's thickness heuristic (0..1; 0: the height-field assumption)
//   step_power   sample distances R * u^power (0.5..4; 2 = XeGTAO's, denser near x)
//   jitter       off | on: per-pixel slice rotation and step offset (a 4x4 Bayer pattern)
//   estimator    mean (the paper's mean over slices) | normalized (over the slices' open
//                hemispheres: exactly 1 where nothing occludes)
//   attenuation  reference (each horizon rise weighted by the reference's 1 - V(r)) | binary
//                (1 within R, faded by falloff: the engines' binary horizon)
//   denoise      radius in pixels of the cross-bilateral blur after it (0..16; 0: none), timed
//                as the sub-pass `denoise`
// Defaults: docs/measured/gtao-rtao-gpu.md (chosen by MSE against the reference on the shipped
// scenes).
#include <memory>

#include "harness/passes/ao_pass_base.h"
#include "harness/passes/gbuffer_pass.h"
#include "harness/passes/gtao_kernel.h"
#include "harness/passes/pass.h"
#include "harness/passes/screen_space_ao.h"
#include "harness/records/columns.h"

namespace ldm {

// Pass's interface (LDM_PASS_DECLARATIONS) and what the pass adds: declarations alike in
// form in every pass's header, each its own.
class Gtao : public AoPassBase {
 public:
  explicit Gtao(StructureParams& params);
  ~Gtao() override;
  LDM_PASS_DECLARATIONS("gtao");
  // What its shaders count in the counting replay (harness/measure/work_counters.h).
  static std::vector<WorkCounter> work_counters();
  Image coverage() const override;
  std::vector<BufferMemory> memory() const override;

  const GtaoSettings& gtao() const { return gtao_; }

 private:
  GtaoSettings gtao_;
  ScreenSpaceAo<GtaoKernel> frame_{"gtao", "denoise"};
};

}  // namespace ldm
