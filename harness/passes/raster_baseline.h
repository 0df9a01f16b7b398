#pragma once
// The cost floors of every structure's construction: the same fragments (the structure's
// fragment source, the same instanced geometry pass) with fragment shaders that store
// nothing of their own. Two sub-passes, both timed on the frames the measurement picks
// (harness/measuring/measurement_session.cpp: every kBaselineFrameStride-th measured frame):
//   raster_baseline  ldm/raster_only.frag, an empty shader without attachments: a driver may
//                    skip shading altogether, so this is the rasteriser's setup and coverage
//                    cost at most
//   raster_touch     ldm/census.frag, one atomicAdd per fragment into its pixel's count: a
//                    side effect no compiler can remove, so every fragment is shaded and
//                    touches memory once, the least any structure must do
// Records relate each structure's construction to both (build_vs_raster,
// build_vs_raster_touch).
#include <cstdint>
#include <string>

#include "harness/gl/gl_objects.h"
#include "harness/measure/gpu_timer.h"
#include "harness/measure/timing_stats.h"
#include "harness/views/view_set.h"
#include "ldm_impls/common/fragment_source.h"

namespace ldm {

// render() times its two sub-passes under kRasterBaselineSubpass and kRasterTouchSubpass
// (harness/measure/timing_stats.h: subsampled, timed on some measured frames only).

class RasterBaseline {
 public:
  // `fragments` must outlive the baseline.
  RasterBaseline(const FragmentSource& fragments, const ViewSet& views);
  void render(GpuTimer* timer) const;
  static bool is_baseline_subpass(const std::string& name) { return is_subsampled_subpass(name); }
  // Fragments the last raster_touch pass counted (a read-back, never timed): the census
  // total when every fragment was shaded.
  uint64_t touched_fragments() const;

 private:
  const FragmentSource& fragments_;
  GlProgram empty_program_, touch_program_;
  mutable GlBuffer counts_;  // cleared by every render()
};

}  // namespace ldm
