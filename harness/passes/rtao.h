#pragma once
// Ray-traced ambient occlusion at low sample counts, on the CPU with Embree: the line "what a
// ray tracer gives for this time budget" beside the LDM AO and HBAO. It is the AO reference's
// own estimator (harness/reference/ao_estimator.h: the pixel-centre primary ray finds the
// G-buffer's point and camera-facing normal, then cosine-weighted visibility rays with the
// same attenuation V = min(d / d_max, 1)^e), run with few samples per pixel and timed. It is a
// reference line for accuracy per sample, not a GPU competitor: its time is CPU wall time
// (TimerSource::CpuWallClock; the record's device is the CPU).
//
// Parameters (--param rtao:KEY=VALUE; comma lists are run axes, e.g. rtao:spp=1,2,4,8):
//   spp          samples per pixel (1..65536, default 1)
//   threads      worker threads (0 = all cores, the default; recorded as rtao_threads)
//   seed         the random stream's seed (default 0x5254414f). Its samples come from pass
//                kRtaoStreamPass of that seed, which no reference reaches (their passes
//                count doublings from 0), so they are independent of the reference's halves
//                whatever --reference-seed says.
//   d_max, visibility   as the LDM AO (also from --d-max / --visibility)
#include <chrono>
#include <memory>

#include "harness/passes/ao_pass_base.h"
#include "harness/passes/pass.h"
#include "harness/records/columns.h"

namespace ldm {

class EmbreeScene;

// The pixel_stream() pass index the rtao samples use (the reference's are below 64).
inline constexpr uint32_t kRtaoStreamPass = 0x80000000u;

// Pass's interface (LDM_PASS_DECLARATIONS) and what the pass adds: declarations alike in
// form in every pass's header, each its own.
class Rtao : public AoPassBase {
 public:
  explicit Rtao(StructureParams& params);
  ~Rtao() override;
  LDM_PASS_DECLARATIONS("rtao");

  // The worker threads a render of the prepared size uses (the parameter, or all cores for
  // 0, at most one per tile).
  int threads_used() const;

 private:
  uint32_t spp_ = 1;
  int threads_ = 0;
  uint64_t seed_ = 0;
  AoSettings ao_;
  int width_ = 0, height_ = 0;
  // The scene in the reference's frame (centred on its bounding sphere) and its BVH, built
  // once in prepare(): the scene is static (rtao_bvh_ms records what the build took).
  std::unique_ptr<Scene> centred_;
  std::unique_ptr<EmbreeScene> embree_;
  double bvh_ms_ = 0;
  Image image_;
};

}  // namespace ldm
