#pragma once
// Horizon-based ambient occlusion (Bavoil, Sainz and Dimitrov 2008; thesis §4.2.3 and
// Listing 15) as a measured peer of the LDM AO: it reads no LDM structure, only the camera's
// G-buffer (shaders/passes/hbao.frag), and is scored against the same Embree AO reference.
//
// Parameters (--param hbao:KEY=VALUE; d_max and visibility also from --d-max/--visibility):
//   directions   N_HBAO, screen-space directions per pixel (1..256, default 8)
//   steps        S_HBAO, ray-marching steps per direction (1..512, default 8)
//   d_max        the radius R in scene units (> 0; default the scene's AO d_max)
//   visibility   scene | attenuated (W = 1 - r^2/R^2) | unattenuated (W = 1 within R)
//   angle_bias   added to the tangent angle, radians (0..1.5, default 0.1)
//   jitter       off | on: per-pixel rotation and step offset from a tiled 4x4 random table
//                (off, the default, uses the same directions everywhere, as the thesis does)
//   blur         radius in pixels of the cross-bilateral blur after the AO (0..16, default 0:
//                none, as the thesis); timed as the sub-pass `blur`
// Every parameter takes a comma list, a run axis (--param hbao:steps=4,8,16).
#include <memory>

#include "harness/passes/ao_pass_base.h"
#include "harness/passes/gbuffer_pass.h"
#include "harness/passes/hbao_kernel.h"
#include "harness/passes/pass.h"
#include "harness/passes/screen_space_ao.h"
#include "harness/records/columns.h"

namespace ldm {

// Pass's interface (LDM_PASS_DECLARATIONS) and what the pass adds: declarations alike in
// form in every pass's header, each its own.
class Hbao : public AoPassBase {
 public:
  explicit Hbao(StructureParams& params);
  ~Hbao() override;
  LDM_PASS_DECLARATIONS("hbao");
  // What its shaders count in the counting replay (harness/measure/work_counters.h).
  static std::vector<WorkCounter> work_counters();
  Image coverage() const override;
  std::vector<BufferMemory> memory() const override;

  const HbaoSettings& hbao() const { return hbao_; }

 private:
  HbaoSettings hbao_;
  ScreenSpaceAo<HbaoKernel> frame_{"hbao", "blur"};
};

}  // namespace ldm
