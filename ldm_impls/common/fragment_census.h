#pragma once
// The fragment census: how many fragments every LDM pixel of every view receives. Measured
// on the GPU with the structures' own geometry pass, it sizes every structure from what the
// scene needs (pool sizes, hash table sizes, the fixed arrays' k) and is the ground truth
// against which each build's stored fragments are checked.
#include <cstdint>
#include <vector>

#include "harness/scene/gpu_scene.h"
#include "harness/views/view_set.h"
#include "ldm_impls/common/fragment_source.h"

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

// Counts the fragments of `source` (shaders/ldm/census.frag) over the pixels of `views`.
FragmentCensus take_fragment_census(const FragmentSource& source, const ViewSet& views);
// The census of `scene` rasterised into `views`.
FragmentCensus take_fragment_census(const GpuScene& scene, const GpuViewSet& views);

}  // namespace ldm
