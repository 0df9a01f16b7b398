// Contention tests of every registered structure (thesis §3.2, §3.4): thousands of
// insertions into a handful of pixels at the same moment, which a rasteriser that shades a
// tile's fragments in order on one thread (llvmpipe) never produces. The structure's own,
// unchanged construction shaders run on a synthetic fragment list through
// SyntheticFragmentSource (one compute invocation per fragment; a pixel's fragments sit
// together, so SIMD lanes of one work group and parallel work groups race on the same
// heads, entries, counts and hash slots). The lists read back through the structure's query
// API must be exactly the known multiset of depths of every pixel: complete, ascending, no
// fragment twice or lost. Parameterised over structure_names(), so a structure registered
// later is tested with no code here.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <map>
#include <random>
#include <string>

#include "harness/scene/scene_loader.h"
#include "ldm_impls/common/ldm_inspector.h"
#include "ldm_impls/common/sizing_driver.h"
#include "ldm_impls/common/synthetic_fragments.h"
#include "support/test_support.h"

namespace ldm {
namespace {

constexpr uint32_t kViews = 2, kResolution = 16;  // 512 LDM pixels
// Hot pixels stay well under the HA-buffer's 255 ages: with 200 fragments a pixel's
// Robin Hood chain runs past the last age at this load (counted drops, not a race).
constexpr uint32_t kHotPixels = 16, kHotFragments = 128;
constexpr uint32_t kWarmPixels = 32, kWarmFragments = 24;
constexpr uint32_t kChunk = 8;  // fragments of one pixel next to each other: a SIMD vector

// A known multiset of depths per pixel and the fragment list that carries it.
struct ContentionWorkload {
  std::vector<std::vector<float>> depths;  // per pixel over all views, ascending
  std::vector<SyntheticFragment> fragments;
};

// Depths on a dyadic grid of the view's depth range, so that a structure that quantises
// depths (the 32-bit HA-buffer's 24-bit fixed point) stores them exactly. Hot pixels repeat
// some depths (coincident surfaces): equal keys must be kept, not merged.
ContentionWorkload make_workload(const ViewSet& views) {
  const float range = views.views[0].depth_range;
  const float step = std::exp2(std::floor(std::log2(range / 4096.0f)));
  std::mt19937 random(20151);
  ContentionWorkload w;
  w.depths.resize(views.total_pixels());
  std::vector<uint32_t> pixels(views.total_pixels());
  for (uint32_t p = 0; p < pixels.size(); ++p) pixels[p] = p;
  std::shuffle(pixels.begin(), pixels.end(), random);
  std::uniform_int_distribution<uint32_t> grid(1, 4000), sparse(0, 3);
  for (uint32_t i = 0; i < pixels.size(); ++i) {
    const uint32_t n = i < kHotPixels                ? kHotFragments
                       : i < kHotPixels + kWarmPixels ? kWarmFragments
                                                      : sparse(random);
    auto& d = w.depths[pixels[i]];
    while (d.size() < n) {
      const float depth = float(grid(random)) * step;
      d.push_back(depth);
      if (i < kHotPixels && d.size() % 4 == 0 && d.size() < n) d.push_back(depth);
    }
  }
  // Each pixel's fragments in random order, cut into chunks; the chunks of all pixels in
  // random order.
  std::vector<std::vector<SyntheticFragment>> chunks;
  for (uint32_t p = 0; p < w.depths.size(); ++p) {
    std::vector<float> order = w.depths[p];
    std::shuffle(order.begin(), order.end(), random);
    for (size_t i = 0; i < order.size(); i += kChunk) {
      chunks.emplace_back();
      for (size_t j = i; j < std::min(order.size(), i + kChunk); ++j)
        chunks.back().push_back({p, order[j]});
    }
    std::sort(w.depths[p].begin(), w.depths[p].end());
  }
  std::shuffle(chunks.begin(), chunks.end(), random);
  for (const auto& chunk : chunks) w.fragments.insert(w.fragments.end(), chunk.begin(), chunk.end());
  return w;
}

// Everything a structure is built from, with the synthetic source in place of the
// rasteriser. The scene is there because BuildInputs names one; no structure draws it.
struct ContentionSetup {
  Scene scene;
  GpuScene gpu_scene;
  ViewSet views;
  GpuViewSet gpu_views;
  ContentionWorkload workload;
  SyntheticFragmentSource source;
  FragmentCensus census;
  SizingPlan oracle_plan, previous_frame_plan;
  BuildInputs inputs;                 // sized from the known census (the oracle policy)
  BuildInputs previous_frame_inputs;  // grown from one fragment per pixel (previous_frame)

  ContentionSetup()
      : scene((test::gl_context(), load_scene("cornell"))),
        gpu_scene(scene, {}),
        views(make_view_set(scene.bounding_sphere(), kViews, kResolution)),
        gpu_views(views),
        workload(make_workload(views)),
        source(views, workload.fragments),
        census(source.expected_census()),
        oracle_plan{SizingPolicy::Oracle, census_needs(census), 0, "known census"},
        previous_frame_plan(plan_without_census({SizingPolicy::PreviousFrame}, census.total_pixels)),
        inputs{gpu_scene, gpu_views, oracle_plan, {}, source},
        previous_frame_inputs{gpu_scene, gpu_views, previous_frame_plan, {}, source} {}
};

const ContentionSetup& setup() {
  static const ContentionSetup s;
  return s;
}

// Pixels whose read-back list is not exactly the expected multiset in ascending order.
uint64_t pixels_not_matching(const ContentionSetup& s, const LdmStructure& structure,
                             const std::string& what) {
  const LdmInspector inspector(structure, s.inputs);
  uint64_t wrong = 0;
  for (uint32_t v = 0; v < s.views.size(); ++v) {
    const auto lists = inspector.read_back(v);
    const double quantum = structure.depth_quantum(s.views.views[v]);
    for (size_t p = 0; p < lists.size(); ++p) {
      const uint64_t pixel = v * s.views.pixels_per_view() + p;
      const auto& expected = s.workload.depths[pixel];
      const auto& actual = lists[p];
      bool same = expected.size() == actual.size();
      for (size_t i = 0; same && i < expected.size(); ++i)
        same = std::abs(double(actual[i]) - double(expected[i])) <= quantum;
      if (!same && ++wrong <= 3) {
        size_t in_order = 0;  // how far the lists agree
        while (in_order < std::min(expected.size(), actual.size()) &&
               std::abs(double(actual[in_order]) - double(expected[in_order])) <= quantum)
          ++in_order;
        ADD_FAILURE() << what << ": pixel " << pixel << " holds " << actual.size()
                      << " depths, expected " << expected.size() << "; they agree up to entry "
                      << in_order;
      }
    }
  }
  return wrong;
}

// A structure and parameters that select another of its paths.
struct Variant {
  std::string structure;
  std::map<std::string, std::string> params;
  SizingPolicy sizing = SizingPolicy::Oracle;
  std::string label() const {
    std::string out = structure;
    for (const auto& [key, value] : params) out += "_" + key + "_" + value;
    if (sizing != SizingPolicy::Oracle) out += std::string("_") + sizing_policy_name(sizing);
    return out;
  }
};

// How gtest names the parameter in test listings (ctest shows it).
void PrintTo(const Variant& v, std::ostream* os) { *os << v.label(); }

std::vector<Variant> every_structure() {
  std::vector<Variant> v;
  for (const std::string& name : structure_names()) v.push_back({name, {}});
  return v;
}

class Contention : public ::testing::TestWithParam<Variant> {};

TEST_P(Contention, ConcurrentInsertionsStoreExactlyTheKnownDepths) {
  const ContentionSetup& s = setup();
  ASSERT_EQ(s.census.max_depth_complexity, kHotFragments);
  const Variant& variant = GetParam();
  const uint64_t retries_before = s.source.retries();
  auto structure = make_structure(variant.structure, StructureParams(variant.params, "contention test"));
  const BuildInputs& inputs =
      variant.sizing == SizingPolicy::PreviousFrame ? s.previous_frame_inputs : s.inputs;
  structure->prepare(inputs);
  SizingDriver driver(*structure, inputs);
  // Repeated builds into the same storage: the clear paths too, and new interleavings.
  for (int build = 0; build < 3; ++build) {
    const std::string what = variant.label() + " build " + std::to_string(build);
    driver.build(nullptr);
    const BuildStats stats = structure->stats();
    EXPECT_EQ(stats.fragments_rasterized, s.census.total_fragments) << what;
    EXPECT_EQ(stats.fragments_stored, s.census.total_fragments) << what;
    EXPECT_EQ(stats.fragments_lost, 0u) << what;
    EXPECT_FALSE(stats.overflow) << what;
    const LdmIntegrity integrity = LdmInspector(*structure, s.inputs).check();
    EXPECT_EQ(integrity.fragments, s.census.total_fragments) << what;
    EXPECT_EQ(integrity.unsorted_pixels, 0u) << what;
    EXPECT_EQ(integrity.overlong_pixels, 0u) << what;
    EXPECT_EQ(pixels_not_matching(s, *structure, what), 0u) << what;
  }
  if (variant.sizing == SizingPolicy::PreviousFrame)  // the first build outgrew the guess
    EXPECT_EQ(driver.rebuilds(), 1u) << variant.label();
  const uint64_t retries = s.source.retries() - retries_before;
  RecordProperty("retries", std::to_string(retries));
  std::cout << variant.label() << ": " << s.census.total_fragments << " fragments x 3 builds, "
            << retries << " retries counted by LDM_COUNT_RETRY (failed compare-and-swap)\n";
}

INSTANTIATE_TEST_SUITE_P(AllStructures, Contention, ::testing::ValuesIn(every_structure()),
                         [](const auto& info) { return info.param.label(); });

// Other paths under the same contention: the §3.4.3 atomic reads, a pool grown and rebuilt
// from a one-node-per-pixel start (the previous_frame sizing policy), post-sorts whose local array is shorter than the hot
// pixels' lists (sorted in place), and the HA-buffer's 64-bit keys.
INSTANTIATE_TEST_SUITE_P(Paths, Contention,
                         ::testing::Values(Variant{"psppsll", {{"atomic_reads", "true"}}},
                                           Variant{"psppsll", {}, SizingPolicy::PreviousFrame},
                                           Variant{"ppsll", {}, SizingPolicy::PreviousFrame},
                                           Variant{"ppsll", {{"local", "8"}}},
                                           Variant{"dfbuffer", {{"local", "8"}}},
                                           // 64-bit keys where the device has 64-bit
                                           // atomics (a GPU: scripts/gpu-suite.sh), else 32
                                           Variant{"habuffer", {{"key_bits", "auto"}}}),
                         [](const auto& info) { return info.param.label(); });

// The synthetic source itself: the census shader run on it counts every listed fragment
// once, pixel by pixel (nothing skipped, nothing run twice).
TEST(ContentionSource, CensusOfTheSyntheticFragmentsIsTheKnownOne) {
  const ContentionSetup& s = setup();
  const FragmentCensus gpu = take_fragment_census(s.source, s.views);
  EXPECT_EQ(gpu.total_fragments, s.census.total_fragments);
  EXPECT_EQ(gpu.counts, s.census.counts);
  EXPECT_EQ(gpu.max_depth_complexity, kHotFragments);
}

// The test produces the contention it is about: PSPPSLL's compare-and-swap fails and its
// retry path runs (on llvmpipe too, whose rasteriser never makes it fail).
TEST(ContentionSource, PsppsllRetryPathIsTaken) {
  const ContentionSetup& s = setup();
  const uint64_t before = s.source.retries();
  auto structure = make_structure("psppsll", StructureParams({}, "contention test"));
  structure->prepare(s.inputs);
  structure->build(s.inputs, nullptr);
  const uint64_t retries = s.source.retries() - before;
  RecordProperty("retries", std::to_string(retries));
  std::cout << "psppsll: " << retries << " retries in one build of " << s.census.total_fragments
            << " fragments\n";
  EXPECT_GT(retries, 0u);
}

}  // namespace
}  // namespace ldm
