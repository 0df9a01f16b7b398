#include "ldm_impls/common/fragment_census.h"

#include <algorithm>

#include "harness/gl/bindings.h"
#include "harness/util/error.h"
#include "ldm_impls/common/ldm_rasterizer.h"
#include "ldm_impls/ldm_structure.h"

namespace ldm {

uint64_t FragmentCensus::fragments_beyond(uint32_t k) const {
  uint64_t lost = 0;
  for (uint32_t n : counts)
    if (n > k) lost += n - k;
  return lost;
}

FragmentCensus take_fragment_census(const GpuScene& scene, const GpuViewSet& views) {
  return take_fragment_census(RasterFragmentSource(scene, views), views.views());
}

FragmentCensus take_fragment_census(const FragmentSource& source, const ViewSet& set) {
  const uint64_t pixels = set.total_pixels();
  GlBuffer counts("census_counts",
                  checked_storage_block("the fragment census", "counts", pixels * sizeof(uint32_t)));
  counts.clear_to_zero();
  counts.bind_storage(kCensusBinding);
  source.run(source.build_program("ldm/census.frag", {}));

  FragmentCensus census;
  census.counts = counts.download_all<uint32_t>();
  census.total_pixels = pixels;
  census.fragments_per_view.assign(set.size(), 0);
  const uint64_t per_view = set.pixels_per_view();
  for (uint64_t i = 0; i < pixels; ++i) {
    const uint32_t n = census.counts[i];
    census.total_fragments += n;
    census.fragments_per_view[i / per_view] += n;
    census.max_depth_complexity = std::max(census.max_depth_complexity, n);
    census.nonempty_pixels += n > 0;
  }
  return census;
}

SizingNeeds census_needs(const FragmentCensus& census) {
  return {census.total_fragments, census.max_depth_complexity};
}

CensusPass::CensusPass(const FragmentSource& source, uint64_t ldm_pixels)
    : source_(source),
      pixels_(ldm_pixels),
      counts_("census_counts", checked_storage_block("the census pass", "counts",
                                                     pixels_ * sizeof(uint32_t))),
      program_(source.build_program("ldm/census.frag", {})) {}

SizingNeeds CensusPass::run() const {
  counts_.clear_to_zero();
  counts_.bind_storage(kCensusBinding);
  source_.run(program_);
  const UintReductionResult r = reduction_.run(counts_, pixels_);
  return {r.sum, r.max};
}

}  // namespace ldm
