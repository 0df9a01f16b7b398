#include "harness/passes/raster_baseline.h"

#include <numeric>

#include "harness/gl/bindings.h"
#include "ldm_impls/ldm_structure.h"

namespace ldm {

RasterBaseline::RasterBaseline(const FragmentSource& fragments, const ViewSet& views)
    : fragments_(fragments),
      empty_program_(fragments.build_program("ldm/raster_only.frag", {})),
      touch_program_(fragments.build_program("ldm/census.frag", {})),
      counts_("raster_touch_counts",
              checked_storage_block("the raster baseline", "counts",
                                    views.total_pixels() * sizeof(uint32_t))) {}

void RasterBaseline::render(GpuTimer* timer) const {
  {
    ScopedSubpass timed(timer, kRasterBaselineSubpass);
    fragments_.run(empty_program_);
  }
  counts_.clear_to_zero();  // before the timed pass: the touch alone is measured
  counts_.bind_storage(kCensusBinding);
  ScopedSubpass timed(timer, kRasterTouchSubpass);
  fragments_.run(touch_program_);
}

uint64_t RasterBaseline::touched_fragments() const {
  const std::vector<uint32_t> counts = counts_.download_all<uint32_t>();
  return std::accumulate(counts.begin(), counts.end(), uint64_t(0));
}

}  // namespace ldm
