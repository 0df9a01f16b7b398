#pragma once
// The fragment census: how many fragments every LDM pixel of every view receives, measured
// on the GPU with the structures' own geometry pass. Two uses, kept apart:
//  - take_fragment_census(): untimed, once per setup, read back in full. The ground truth
//    against which each build's stored fragments are checked (verification), and the
//    sizes of the `oracle` sizing policy (ldm_impls/common/sizing.h), labelled as such.
//  - CensusPass: the `census` sizing policy's per-frame sub-pass, timed and charged to the
//    build: the same counting pass, reduced on the GPU, two words read back.
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "harness/gl/gl_objects.h"
#include "harness/scene/gpu_scene.h"
#include "harness/views/view_set.h"
#include "ldm_impls/common/fragment_source.h"
#include "ldm_impls/common/sizing.h"
#include "ldm_impls/common/uint_reduction.h"

namespace ldm {

struct FragmentCensus {
  uint64_t total_fragments = 0;
  uint32_t max_depth_complexity = 0;
  uint64_t nonempty_pixels = 0;
  uint64_t total_pixels = 0;
  std::vector<uint64_t> fragments_per_view;
  std::vector<uint32_t> counts;  // per pixel, all views (index ldm_pixel_index)

  double mean_depth_complexity() const {  // over non-empty pixels
    return nonempty_pixels ? double(total_fragments) / double(nonempty_pixels) : 0.0;
  }
  // Fragments lost by an array of k entries per pixel: sum over pixels of max(0, n - k).
  uint64_t fragments_beyond(uint32_t k) const;
};

// The depth-complexity profile of a census: how list lengths are distributed over the LDM
// pixels that hold any fragment. It is what explains a ranking: a fixed array sized for the
// deepest pixel wastes what the p50 does not use, and a list's memory follows the total.
struct DepthProfile {
  // pixels_by_length[n]: LDM pixels (all views) holding exactly n fragments, n = 0 .. max.
  std::vector<uint64_t> pixels_by_length;
  uint64_t nonempty_pixels = 0;
  uint32_t p50 = 0, p90 = 0, p99 = 0, max = 0;  // over the non-empty pixels (nearest rank)

  // Share of the non-empty pixels holding more than k fragments (what an array of k
  // entries drops some of).
  double share_above(uint32_t k) const;
  // The smallest length n such that a share of at least q of the non-empty pixels hold at
  // most n fragments (0 when no pixel holds any).
  uint32_t quantile(double q) const;
  // "1:812;2-3:340;4-7:95;..." pixels per power-of-two bin of lengths, non-empty pixels only.
  std::string histogram_text() const;
};
DepthProfile depth_profile(const FragmentCensus& census);

// Counts the fragments of `source` (shaders/ldm/census.frag) over the pixels of `views`.
FragmentCensus take_fragment_census(const FragmentSource& source, const ViewSet& views);
// The census of `scene` rasterised into `views`.
FragmentCensus take_fragment_census(const GpuScene& scene, const GpuViewSet& views);

// What the oracle policy hands a structure: the census's totals (nothing else of it).
SizingNeeds census_needs(const FragmentCensus& census);

// The census as a sub-pass of a frame: clear the counts, count every fragment, reduce the
// counts to (total, deepest pixel) on the GPU and read those back (the sync a renderer that
// sizes from a census pays). The caller times it.
class CensusPass {
 public:
  CensusPass(const FragmentSource& source, uint64_t ldm_pixels);
  SizingNeeds run() const;
  uint64_t counts_bytes() const { return counts_.bytes(); }

 private:
  const FragmentSource& source_;
  uint64_t pixels_ = 0;
  mutable GlBuffer counts_;
  GlProgram program_;
  UintReduction reduction_;
};

}  // namespace ldm
