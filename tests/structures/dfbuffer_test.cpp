// The DF-buffer (thesis §3.2.10): its parallel prefix sum against a CPU scan on awkward
// sizes; its lists against PSPPSLL's on the same scene and views, bit for bit, through the
// local array and the in-place path; and its exact sizing: a scan total that differs from
// the storage it was given is flagged, and what does not fit is counted as lost.
#include <gtest/gtest.h>

#include <numeric>
#include <random>

#include "harness/util/error.h"
#include "ldm_impls/dfbuffer/prefix_sum.h"
#include "structures/structure_test_support.h"

namespace ldm {
namespace {

using test::LdmFixture;

constexpr uint32_t kSentinel = 0xdeadbeefu;

// The GPU scan of `values`, read back with two guard words past output[count].
std::vector<uint32_t> gpu_exclusive_scan(const std::vector<uint32_t>& values) {
  test::gl_context();
  const PrefixSum scan(values.size());
  const GlBuffer input("scan_input", values.size() * sizeof(uint32_t), values.data());
  const std::vector<uint32_t> guarded(values.size() + 3, kSentinel);
  const GlBuffer output("scan_output", guarded.size() * sizeof(uint32_t), guarded.data());
  scan.run(input, output);
  return output.download_all<uint32_t>();
}

void expect_scan_matches_cpu(size_t count, uint32_t max_value, uint32_t seed) {
  std::mt19937 random(seed);
  std::uniform_int_distribution<uint32_t> value(0, max_value);
  std::vector<uint32_t> values(count);
  for (auto& v : values) v = value(random);
  std::vector<uint32_t> expected(count + 1, 0);
  std::exclusive_scan(values.begin(), values.end(), expected.begin(), 0u);
  expected[count] = std::accumulate(values.begin(), values.end(), 0u);

  const std::vector<uint32_t> actual = gpu_exclusive_scan(values);
  ASSERT_EQ(actual.size(), count + 3);
  size_t wrong = 0;
  for (size_t i = 0; i <= count; ++i)
    if (actual[i] != expected[i] && ++wrong <= 3)
      ADD_FAILURE() << "count " << count << ": offset[" << i << "] = " << actual[i] << ", expected "
                    << expected[i];
  EXPECT_EQ(wrong, 0u) << "count " << count;
  EXPECT_EQ(actual[count + 1], kSentinel) << "the scan wrote past output[count]";
  EXPECT_EQ(actual[count + 2], kSentinel) << "the scan wrote past output[count]";
}

TEST(DfBufferPrefixSum, MatchesCpuScanOnAwkwardSizes) {
  // One block is 1024 values; count + 1 are scanned (the total comes last).
  for (size_t count :
       {size_t(1), size_t(2), size_t(63), size_t(64), size_t(65), size_t(1022), size_t(1023),
        size_t(1024), size_t(1025), size_t(4095), size_t(4096 * 64 + 17)})
    expect_scan_matches_cpu(count, 300, uint32_t(count));
}

TEST(DfBufferPrefixSum, ThreeLevelsMatchCpuScan) {
  const size_t count = 1024 * 1024 + 5;  // 1025 blocks, then 2, then 1
  EXPECT_EQ(PrefixSum(count).levels(), 3u);
  expect_scan_matches_cpu(count, 400, 7);
}

TEST(DfBufferPrefixSum, AllZeroCountsGiveAllZeroOffsets) {
  const std::vector<uint32_t> actual = gpu_exclusive_scan(std::vector<uint32_t>(5000, 0));
  for (size_t i = 0; i <= 5000; ++i) ASSERT_EQ(actual[i], 0u) << "offset " << i;
}

TEST(DfBuffer, SmallLocalArraysSortInPlaceAndCountIt) {
  test::expect_in_place_sort_matches_psppsll("dfbuffer", "cornell", 8, 32);
  test::expect_in_place_sort_matches_psppsll("dfbuffer", "atrium", 8, 32);
}

// A DF-buffer prepared from an oracle plan that disagrees with the scene by `delta`
// fragments, as if the scene had changed since the census.
struct MisSizedDfBuffer {
  SizingPlan plan;
  std::unique_ptr<BuildInputs> inputs;
  std::unique_ptr<LdmStructure> structure;
  BuildStats stats;

  MisSizedDfBuffer(const LdmFixture& f, int64_t delta) : plan(f.sizing) {
    plan.initial.fragments = uint64_t(int64_t(plan.initial.fragments) + delta);
    inputs = std::make_unique<BuildInputs>(
        BuildInputs{*f.gpu_scene, *f.gpu_views, plan, {}, *f.raster});
    structure = make_structure("dfbuffer", {});
    structure->prepare(*inputs);
    structure->build(*inputs, nullptr);
    stats = structure->stats();
  }
};

TEST(DfBuffer, ScanTotalBeyondTheStorageIsOverflowAndCountsTheLoss) {
  const LdmFixture f("atrium", 8, 32);
  const uint64_t total = f.census.total_fragments;
  const MisSizedDfBuffer d(f, -100);
  EXPECT_TRUE(d.stats.overflow);
  EXPECT_EQ(test::stats_counter(d.stats, "scan_total"), double(total));
  EXPECT_EQ(test::stats_counter(d.stats, "storage_mismatch"), 1.0);
  EXPECT_EQ(d.stats.fragments_rasterized, total);
  EXPECT_EQ(d.stats.fragments_stored, total - 100);
  EXPECT_EQ(d.stats.fragments_lost, 100u);
  const LdmIntegrity integrity = LdmInspector(*d.structure, *d.inputs).check();
  EXPECT_EQ(integrity.fragments, total - 100);
  EXPECT_EQ(integrity.unsorted_pixels, 0u);
}

TEST(DfBuffer, ScanTotalBelowTheStorageIsFlaggedButLosesNothing) {
  const LdmFixture f("cornell", 8, 32);
  const auto reference = test::build_psppsll_reference(f);
  const MisSizedDfBuffer d(f, +100);
  EXPECT_FALSE(d.stats.overflow);
  EXPECT_EQ(test::stats_counter(d.stats, "storage_mismatch"), 1.0);
  EXPECT_EQ(d.stats.fragments_stored, f.census.total_fragments);
  EXPECT_EQ(d.stats.fragments_lost, 0u);
  test::expect_bit_identical_lists(reference.lists, test::read_all_views(*d.structure, f),
                                   "dfbuffer with 100 spare slots");
}

TEST(DfBuffer, MemoryIsExactlySizedFromTheCensus) {
  const LdmFixture f("cornell", 8, 32);
  const auto s = f.build("dfbuffer");
  const BuildStats stats = s->stats();
  EXPECT_EQ(test::stats_counter(stats, "storage_mismatch"), 0.0);
  EXPECT_EQ(test::stats_counter(stats, "unfilled_slots"), 0.0);
  EXPECT_EQ(test::sizing_value(*s, "depth_capacity"), std::to_string(f.census.total_fragments));
  std::map<std::string, BufferMemory> by_name;
  for (const BufferMemory& m : s->memory()) by_name[m.name] = m;
  ASSERT_EQ(by_name.count("depths"), 1u);
  EXPECT_EQ(by_name["depths"].allocated, f.census.total_fragments * 4);
  EXPECT_EQ(by_name["depths"].used, f.census.total_fragments * 4);
  EXPECT_EQ(by_name["counts"].allocated, f.census.total_pixels * 4);
  EXPECT_EQ(by_name["offsets"].allocated, (f.census.total_pixels + 1) * 4);
}

TEST(DfBuffer, OutOfRangeParametersAreUserErrors) {
  test::expect_params_checked("dfbuffer", {{{"local", "0"}}, {{"local", "129"}}, {{"pool", "grow"}}},
                              {{{"local", "1"}}});
}

}  // namespace
}  // namespace ldm
