#include "ldm_impls/common/synthetic_fragments.h"

#include <algorithm>
#include <cstring>

#include "harness/gl/bindings.h"
#include "harness/util/error.h"
#include "ldm_impls/common/compute_grid.h"

namespace ldm {
namespace {
constexpr uint64_t kSyntheticGroupSize = 64;  // local_size_x of synthetic_fragments.comp
}  // namespace

SyntheticFragmentSource::SyntheticFragmentSource(const ViewSet& views,
                                                 const std::vector<SyntheticFragment>& fragments)
    : views_(views), list_(fragments) {
  std::vector<uint32_t> words;
  words.reserve(2 * fragments.size());
  for (const SyntheticFragment& f : fragments) {
    if (f.pixel >= views.total_pixels())
      throw GpuError("synthetic fragment at pixel " + std::to_string(f.pixel) + " of " +
                     std::to_string(views.total_pixels()));
    uint32_t depth_bits;
    std::memcpy(&depth_bits, &f.depth, sizeof depth_bits);
    words.push_back(f.pixel);
    words.push_back(depth_bits);
  }
  if (words.empty()) words.assign(2, 0);  // a buffer cannot be empty; the count guards it
  fragments_ = GlBuffer("synthetic_fragments", words.size() * sizeof(uint32_t), words.data());
  retries_ = GlBuffer("synthetic_retries", sizeof(uint32_t));
  retries_.clear_to_zero();
}

GlProgram SyntheticFragmentSource::build_program(const std::string& fragment_file,
                                                 const ShaderDefines& defines) const {
  ShaderDefines all = binding_defines();
  all.values.insert(all.values.end(), defines.values.begin(), defines.values.end());
  all.set("LDM_SYNTHETIC_FRAGMENTS", 1);
  all.set("LDM_SYNTHETIC_FRAGMENTS_BINDING", kSyntheticFragmentsBinding);
  all.set("LDM_SYNTHETIC_RETRY_BINDING", kSyntheticRetryBinding);
  all.set("LDM_SYNTHETIC_FRAGMENT_COUNT", std::to_string(list_.size()) + "u");
  all.set("LDM_SYNTHETIC_PIXELS_PER_VIEW", std::to_string(views_.pixels_per_view()) + "u");
  // The fragment shader's main() becomes a function the wrapper calls.
  all.set("main", "ldm_fragment_main");
  return ldm::build_program({{GL_COMPUTE_SHADER, "ldm/synthetic_fragments.comp", {fragment_file}}},
                            all);
}

void SyntheticFragmentSource::run(const GlProgram& program) const {
  program.use();
  fragments_.bind_storage(kSyntheticFragmentsBinding);
  retries_.bind_storage(kSyntheticRetryBinding);
  dispatch_linear_groups(groups_for(list_.size(), kSyntheticGroupSize));
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_ATOMIC_COUNTER_BARRIER_BIT |
                  GL_BUFFER_UPDATE_BARRIER_BIT);
}

uint64_t SyntheticFragmentSource::retries() const {
  uint32_t retries = 0;
  retries_.download(&retries, sizeof retries);
  return retries;
}

FragmentCensus SyntheticFragmentSource::expected_census() const {
  FragmentCensus census;
  census.total_pixels = views_.total_pixels();
  census.counts.assign(census.total_pixels, 0);
  census.fragments_per_view.assign(views_.size(), 0);
  for (const SyntheticFragment& f : list_) {
    ++census.counts[f.pixel];
    ++census.fragments_per_view[f.pixel / views_.pixels_per_view()];
  }
  census.total_fragments = list_.size();
  for (uint32_t n : census.counts) {
    census.max_depth_complexity = std::max(census.max_depth_complexity, n);
    census.nonempty_pixels += n > 0;
  }
  return census;
}

}  // namespace ldm
