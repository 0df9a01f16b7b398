// The sizing policies (ldm_impls/common/sizing.h) on every structure: each gives the
// oracle's lists when its capacity suffices; previous_frame from a too-small first guess
// overflows, rebuilds once (timed, counted) and ends exact; the budget policy stays within
// its bytes and counts what it loses exactly; the census policy times its census.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "harness/util/error.h"
#include "ldm_impls/common/sizing_driver.h"
#include "structures/structure_test_support.h"

namespace ldm {
namespace {

using test::LdmFixture;

SizingSettings policy(SizingPolicy p, uint64_t budget_bytes = 0) {
  SizingSettings s;
  s.policy = p;
  s.budget_bytes = budget_bytes;
  return s;
}

uint64_t allocated_bytes(const LdmStructure& s) {
  uint64_t total = 0;
  for (const BufferMemory& m : s.memory()) total += m.allocated;
  return total;
}

bool timed(const FrameTimes& times, const std::string& subpass) {
  return std::any_of(times.begin(), times.end(), [&](const auto& t) { return t.first == subpass; });
}

// One frame of the driver with a wall-clock timer; the sub-passes it timed.
FrameTimes driven_frame(SizingDriver& driver) {
  GpuTimer timer(TimerSource::FencedWallClock);
  timer.begin_frame();
  driver.build(&timer);
  return timer.end_frame();
}

// Every fragment stored, and the lists bit for bit those of the same structure under the
// oracle policy.
void expect_oracle_lists(const std::string& name, SizingPolicy p, const std::string& scene,
                         uint64_t budget_bytes = 0) {
  const LdmFixture oracle(scene, 8, 32);
  const LdmFixture f(scene, 8, 32, policy(p, budget_bytes));
  const std::string what = name + " under " + sizing_policy_name(p);
  auto s = f.prepare(name);
  SizingDriver driver(*s, *f.inputs);
  for (int frame = 0; frame < 2; ++frame) driven_frame(driver);
  const BuildStats stats = s->stats();
  EXPECT_EQ(stats.fragments_lost, 0u) << what;
  EXPECT_EQ(stats.fragments_stored, f.census.total_fragments) << what;
  EXPECT_EQ(stats.fragments_rasterized, f.census.total_fragments) << what;
  test::expect_bit_identical_lists(test::read_all_views(*oracle.build(name), oracle),
                                   test::read_all_views(*s, f), what);
}

TEST(SizingPolicy, CensusGivesTheOraclesListsOnEveryStructure) {
  for (const std::string& name : structure_names())
    expect_oracle_lists(name, SizingPolicy::Census, "atrium");
}

TEST(SizingPolicy, PreviousFrameGivesTheOraclesListsOnEveryStructure) {
  for (const std::string& name : structure_names())
    expect_oracle_lists(name, SizingPolicy::PreviousFrame, "atrium");
}

TEST(SizingPolicy, AnAmpleBudgetGivesTheOraclesListsOnEveryStructure) {
  for (const std::string& name : structure_names())
    expect_oracle_lists(name, SizingPolicy::Budget, "atrium", uint64_t(8) << 20);
}

TEST(SizingPolicy, CensusPolicyTimesItsCensusOrTheDfBuffersReadback) {
  const LdmFixture f("cornell", 8, 32, policy(SizingPolicy::Census));
  for (const std::string& name : structure_names()) {
    auto s = f.prepare(name);
    SizingDriver driver(*s, *f.inputs);
    const FrameTimes first = driven_frame(driver);
    const FrameTimes second = driven_frame(driver);
    // The DF-buffer's count pass and scan are its census: it is not charged a second one.
    const bool own = name == "dfbuffer";
    EXPECT_EQ(timed(first, "census"), !own) << name;
    EXPECT_EQ(timed(second, "census"), !own) << name;
    EXPECT_EQ(timed(second, "readback"), own) << name;
    EXPECT_TRUE(timed(first, "reallocate")) << name << ": the first census grows the storage";
    EXPECT_FALSE(timed(second, "reallocate")) << name << ": nothing changed since";
    EXPECT_EQ(driver.rebuilds(), 0u) << name;
  }
}

TEST(SizingPolicy, PreviousFrameFromATooSmallGuessRebuildsOnceAndEndsExact) {
  const LdmFixture f("atrium", 8, 32, policy(SizingPolicy::PreviousFrame));
  // One fragment per pixel is too small for every structure here: the atrium has more
  // fragments than the HA-buffer's guessed table (pixels / 0.75) and pixels deeper than 1.
  ASSERT_GT(double(f.census.total_fragments), 1.4 * double(f.census.total_pixels));
  ASSERT_GT(f.census.max_depth_complexity, 1u);
  const LdmFixture oracle("atrium", 8, 32);
  for (const std::string& name : structure_names()) {
    auto s = f.prepare(name);
    SizingDriver driver(*s, *f.inputs);
    const FrameTimes first = driven_frame(driver);
    EXPECT_TRUE(timed(first, "readback")) << name;
    EXPECT_TRUE(timed(first, "rebuild")) << name << ": the first build overflowed";
    EXPECT_EQ(driver.rebuilds(), 1u) << name;
    const FrameTimes second = driven_frame(driver);
    EXPECT_FALSE(timed(second, "rebuild")) << name;
    EXPECT_EQ(driver.rebuilds(), 1u) << name << ": sized from its own counters, once is enough";
    const BuildStats stats = s->stats();
    EXPECT_EQ(stats.fragments_lost, 0u) << name;
    EXPECT_EQ(stats.fragments_stored, f.census.total_fragments) << name;
    test::expect_bit_identical_lists(test::read_all_views(*oracle.build(name), oracle),
                                     test::read_all_views(*s, f), name + " after its rebuild");
  }
}

bool has_counter(const BuildStats& stats, const std::string& name) {
  return std::any_of(stats.counters.begin(), stats.counters.end(),
                     [&](const auto& c) { return c.first == name; });
}

// Issue 21: from previous_frame's guess of one fragment per pixel the atrium's table is far
// too small. The first build stops once more fragments arrive than the table is sized for
// (instead of probing a full table up to max_age + 1 slots per fragment), still counts every
// fragment exactly (stored + lost = rasterised: the build is flagged, never silently short),
// and the one rebuild, sized from that count, is exact and runs the unchanged program.
TEST(SizingPolicy, HaBufferFirstBuildFromAFarTooSmallGuessStopsOnceTheTableIsKnownTooSmall) {
  const LdmFixture f("atrium", 8, 32, policy(SizingPolicy::PreviousFrame));
  const uint64_t total = f.census.total_fragments;
  {
    auto s = f.prepare("habuffer");
    const uint64_t table = std::stoull(test::sizing_value(*s, "table_entries"));
    ASSERT_LT(table, total) << "the guessed table must be too small for this test";
    s->build(*f.inputs, nullptr);
    const BuildStats first = s->stats();
    EXPECT_TRUE(first.overflow);
    // Those beyond what the table is sized for (|H| * load_factor 0.75) stop at once.
    const uint64_t sized_for = uint64_t(std::floor(double(table) * 0.75));
    EXPECT_EQ(test::stats_counter(first, "stopped_table_too_small"), double(total - sized_for));
    EXPECT_LE(first.fragments_stored, table);
    EXPECT_EQ(first.fragments_stored + first.fragments_lost, total) << "the loss is counted exactly";
    EXPECT_EQ(first.fragments_rasterized, total);
    const SizingNeeds needs = s->needed();
    EXPECT_TRUE(needs.lost);
    EXPECT_EQ(needs.fragments, total) << "the rebuild is sized from the exact count";
    EXPECT_FALSE(s->fits(needs));
  }
  const LdmFixture oracle("atrium", 8, 32);
  auto s = f.prepare("habuffer");
  SizingDriver driver(*s, *f.inputs);
  const FrameTimes first = driven_frame(driver);
  EXPECT_TRUE(timed(first, "rebuild"));
  EXPECT_EQ(driver.rebuilds(), 1u);
  driven_frame(driver);
  EXPECT_EQ(driver.rebuilds(), 1u);
  const BuildStats stats = s->stats();
  EXPECT_FALSE(has_counter(stats, "stopped_table_too_small")) << "later builds run the plain program";
  EXPECT_EQ(stats.fragments_lost, 0u);
  EXPECT_EQ(stats.fragments_stored, total);
  test::expect_bit_identical_lists(test::read_all_views(*oracle.build("habuffer"), oracle),
                                   test::read_all_views(*s, f), "habuffer after its rebuild");
}

// A guess that holds, and a table under-sized on purpose (load_factor > 1), never stop early:
// what they store is what the plain program stores.
TEST(SizingPolicy, HaBufferStopsEarlyOnlyFromAGuessThatMustBeRebuilt) {
  SizingSettings ample = policy(SizingPolicy::PreviousFrame);
  ample.initial_per_pixel = 64;
  const LdmFixture f("atrium", 8, 32, ample);
  {
    auto s = f.prepare("habuffer");
    SizingDriver driver(*s, *f.inputs);
    driven_frame(driver);
    EXPECT_EQ(test::stats_counter(s->stats(), "stopped_table_too_small"), 0.0) << "the guess held";
    driven_frame(driver);
    EXPECT_EQ(driver.rebuilds(), 0u);
    const BuildStats stats = s->stats();
    EXPECT_FALSE(has_counter(stats, "stopped_table_too_small")) << "plain program after the first frame";
    EXPECT_EQ(stats.fragments_stored, f.census.total_fragments);
  }
  const LdmFixture small("atrium", 8, 32, policy(SizingPolicy::PreviousFrame));
  auto packed = small.prepare("habuffer", {{"load_factor", "4"}});
  packed->build(*small.inputs, nullptr);
  const BuildStats stats = packed->stats();
  EXPECT_FALSE(has_counter(stats, "stopped_table_too_small"));
  EXPECT_EQ(stats.fragments_stored + stats.fragments_lost, small.census.total_fragments);
}

TEST(SizingPolicy, BudgetOverflowIsCountedExactly) {
  const LdmFixture oracle("atrium", 8, 32);
  for (const std::string& name : structure_names()) {
    // 60% of what the oracle allocates: within reach of every structure's fixed buffers,
    // too small for its fragments.
    const uint64_t budget = allocated_bytes(*oracle.build(name)) * 6 / 10;
    const LdmFixture f("atrium", 8, 32, policy(SizingPolicy::Budget, budget));
    const auto s = f.build(name);
    const BuildStats stats = s->stats();
    const uint64_t total = f.census.total_fragments;
    EXPECT_LE(allocated_bytes(*s), budget) << name;
    EXPECT_TRUE(stats.overflow) << name;
    EXPECT_GT(stats.fragments_lost, 0u) << name;
    EXPECT_EQ(stats.fragments_stored + stats.fragments_lost, total) << name;
    const LdmIntegrity integrity = LdmInspector(*s, *f.inputs).check();
    EXPECT_EQ(integrity.fragments, stats.fragments_stored) << name;
    EXPECT_EQ(integrity.unsorted_pixels, 0u) << name;
    // Where the loss follows from the size alone, it is exactly that.
    if (name == "psppsll" || name == "ppsll") {
      const uint64_t nodes = std::stoull(test::sizing_value(*s, "pool_capacity_nodes"));
      EXPECT_EQ(stats.fragments_lost, total - nodes) << name;
      EXPECT_EQ(test::sizing_value(*s, "pool_size_source"), "budget");
    } else if (name == "dfbuffer") {
      const uint64_t slots = std::stoull(test::sizing_value(*s, "depth_capacity"));
      EXPECT_EQ(stats.fragments_lost, total - slots) << name;
    } else if (name == "ppfla" || name == "psppfla") {
      const uint32_t k = uint32_t(std::stoul(test::sizing_value(*s, "k")));
      EXPECT_EQ(stats.fragments_lost, f.census.fragments_beyond(k)) << name;
      EXPECT_EQ(test::sizing_value(*s, "k_source"), "budget");
    }
  }
}

TEST(SizingPolicy, ExplicitSizeParametersOverrideThePolicy) {
  const LdmFixture f("atrium", 8, 32, policy(SizingPolicy::PreviousFrame));
  for (const auto& [name, params] :
       std::vector<std::pair<std::string, test::Params>>{{"ppfla", {{"k", "2"}}},
                                                         {"psppsll", {{"capacity", "1000"}}}}) {
    auto s = f.prepare(name, params);
    SizingDriver driver(*s, *f.inputs);
    driven_frame(driver);
    driven_frame(driver);
    EXPECT_EQ(driver.rebuilds(), 0u) << name << ": a fixed size is not resized";
    EXPECT_GT(s->stats().fragments_lost, 0u) << name;
  }
}

TEST(SizingPolicy, ABudgetBelowTheFixedBuffersIsAUserError) {
  const LdmFixture f("cornell", 8, 32, policy(SizingPolicy::Budget, 1024));
  for (const std::string& name : structure_names())
    EXPECT_THROW(f.prepare(name), UserError) << name;
}

}  // namespace
}  // namespace ldm
