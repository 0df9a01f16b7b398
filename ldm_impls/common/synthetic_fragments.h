#pragma once
// A fragment source without a rasteriser: a given list of (pixel, depth) fragments, each run
// through a structure's own geometry-pass fragment shader by one compute invocation
// (shaders/ldm/synthetic_fragments.comp wraps the unchanged shader). Invocations of a work
// group run on SIMD lanes side by side and work groups run in parallel, so fragments of one
// pixel listed close together insert at the same moment: the contention that the lock-free
// paths (compare-and-swap retries, displacement, atomic counts) are written for and that a
// rasteriser shading a tile's fragments in order never produces. Used by the contention
// tests (tests/structures/contention_test.cpp).
#include <cstdint>
#include <vector>

#include "harness/gl/gl_objects.h"
#include "harness/views/view_set.h"
#include "ldm_impls/common/fragment_census.h"
#include "ldm_impls/common/fragment_source.h"

namespace ldm {

struct SyntheticFragment {
  uint32_t pixel;  // over all views: view * R_LDM^2 + y * R_LDM + x
  float depth;
};

class SyntheticFragmentSource : public FragmentSource {
 public:
  // Every pixel must lie within `views`. The fragments run in the order given, 64 to a
  // work group.
  SyntheticFragmentSource(const ViewSet& views, const std::vector<SyntheticFragment>& fragments);

  GlProgram build_program(const std::string& fragment_file,
                          const ShaderDefines& defines) const override;
  void run(const GlProgram& program) const override;
  ProbeStage stage() const override { return ProbeStage::Compute; }

  // Retry paths the fragment shaders took (LDM_COUNT_RETRY in ldm/ldm_fragment.glsl) over
  // every run() so far.
  uint64_t retries() const;
  // The census of the list, counted on the CPU: what the GPU census must find.
  FragmentCensus expected_census() const;

 private:
  ViewSet views_;
  std::vector<SyntheticFragment> list_;
  GlBuffer fragments_, retries_;
};

}  // namespace ldm
