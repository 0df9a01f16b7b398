#include "ldm_impls/common/fragment_census.h"

#include <algorithm>
#include <cmath>

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

double DepthProfile::share_above(uint32_t k) const {
  if (nonempty_pixels == 0) return 0.0;
  uint64_t above = 0;
  for (size_t n = size_t(k) + 1; n < pixels_by_length.size(); ++n) above += pixels_by_length[n];
  return double(above) / double(nonempty_pixels);
}

uint32_t DepthProfile::quantile(double q) const {
  if (nonempty_pixels == 0) return 0;
  // Nearest rank: the rank-th smallest length, rank = ceil(q * count), at least 1.
  const auto rank = std::max<uint64_t>(1, uint64_t(std::ceil(q * double(nonempty_pixels))));
  uint64_t seen = 0;
  for (size_t n = 1; n < pixels_by_length.size(); ++n) {
    seen += pixels_by_length[n];
    if (seen >= rank) return uint32_t(n);
  }
  return max;
}

std::string DepthProfile::histogram_text() const {
  std::string text;
  for (uint64_t lo = 1; lo < pixels_by_length.size(); lo *= 2) {
    const uint64_t hi = std::min<uint64_t>(2 * lo - 1, pixels_by_length.size() - 1);
    uint64_t pixels = 0;
    for (uint64_t n = lo; n <= hi; ++n) pixels += pixels_by_length[n];
    text += (text.empty() ? "" : ";") + std::to_string(lo) +
            (hi > lo ? "-" + std::to_string(hi) : std::string()) + ":" + std::to_string(pixels);
  }
  return text;
}

DepthProfile depth_profile(const FragmentCensus& census) {
  DepthProfile p;
  p.max = census.max_depth_complexity;
  p.pixels_by_length.assign(size_t(p.max) + 1, 0);
  for (uint32_t n : census.counts) ++p.pixels_by_length[n];
  p.nonempty_pixels = census.total_pixels - p.pixels_by_length[0];
  p.p50 = p.quantile(0.50);
  p.p90 = p.quantile(0.90);
  p.p99 = p.quantile(0.99);
  return p;
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
