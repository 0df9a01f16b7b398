// What every registered structure must do, whatever it is: one TEST_P per property over
// structure_names(), so a newly registered structure is tested without a test file of its
// own (its own file keeps only what is specific to it). PSPPSLL, checked against Embree in
// tests/psppsll, is the yardstick.
//
//  - lists: with default parameters, every fragment stored and reachable, sorted, and the
//    same lists as PSPPSLL's (bit for bit; within depth_quantum() where depths are quantised)
//  - repeated builds: the same lists every time, and BuildHealth's verdict over them is ok
//  - lossy configurations: the loss is counted exactly, the kept lists are the pixels' own
//    fragments in order, and the verdict is lossy, never invalid
//  - AO: through the structure as through PSPPSLL (bit-identical for exact depths, within
//    the bound the quantum implies otherwise)
//  - stats() and memory() are self-contained: any order, same answers
//  - the shared measurement path: measure() judges a default build ok
//  - under contention (contention_test.cpp, over the same registry and some parameter
//    variants): concurrent insertions into a few pixels store exactly the known depths
#include <gtest/gtest.h>

#include <functional>
#include <optional>

#include "harness/records/harness_columns.h"
#include "harness/measuring/measurement.h"
#include "ldm_impls/common/build_health.h"
#include "structures/structure_test_support.h"
#include "support/measurement_request.h"

namespace ldm {
namespace {

using test::LdmFixture;
using test::Params;

// A configuration of each structure whose capacity is below the scene's fragments, from
// the census; nullopt where the structure has no capacity to get wrong (the DF-buffer is
// sized by its own count pass; its mis-sizing is tested in dfbuffer_test.cpp). A new
// structure must add its line: EveryStructureSaysHowItCanBeLossy fails until it does.
using LossyConfiguration = std::function<std::optional<Params>(const FragmentCensus&)>;

// `param` at half the scene's fragments: a pool too small for them.
LossyConfiguration half_the_fragments(const std::string& param) {
  return [param](const FragmentCensus& c) -> std::optional<Params> {
    return Params{{param, std::to_string(c.total_fragments / 2)}};
  };
}

// `param` at half the scene's deepest pixel: too few slots for it.
LossyConfiguration half_the_depth(const std::string& param) {
  return [param](const FragmentCensus& c) -> std::optional<Params> {
    return Params{{param, std::to_string(c.max_depth_complexity / 2)}};
  };
}

const std::map<std::string, LossyConfiguration>& lossy_configurations() {
  static const std::map<std::string, LossyConfiguration> table = {
      {"psppsll", half_the_fragments("capacity")},
      {"ppsll", half_the_fragments("capacity")},
      {"dfbuffer", [](const FragmentCensus&) -> std::optional<Params> { return std::nullopt; }},
      {"habuffer", half_the_depth("max_age")},
      {"ppfla", half_the_depth("k")},
      {"psppfla", half_the_depth("k")},
  };
  return table;
}

class StructureConformance : public ::testing::TestWithParam<std::string> {
 protected:
  const std::string& structure() const { return GetParam(); }
};

double depth_quantum(const LdmStructure& s, const LdmFixture& f) {
  return s.depth_quantum(f.views.views[0]);
}

void expect_lists_equal_psppsll(const std::string& name, const std::string& scene, uint32_t n,
                                uint32_t r) {
  const std::string what = name + " on " + scene;
  const LdmFixture f(scene, n, r);
  ASSERT_GT(f.census.total_fragments, 0u);
  const auto reference = test::build_psppsll_reference(f);
  const auto s = f.build(name);
  const BuildStats stats = s->stats();
  EXPECT_EQ(stats.fragments_rasterized, f.census.total_fragments) << what;
  EXPECT_EQ(stats.fragments_stored, f.census.total_fragments) << what;
  EXPECT_EQ(stats.fragments_lost, 0u) << what;
  EXPECT_FALSE(stats.overflow) << what;
  const LdmIntegrity integrity = LdmInspector(*s, *f.inputs).check();
  EXPECT_EQ(integrity.fragments, f.census.total_fragments) << what;
  EXPECT_EQ(integrity.unsorted_pixels, 0u) << what;
  EXPECT_EQ(integrity.overlong_pixels, 0u) << what;
  const auto lists = test::read_all_views(*s, f);
  const double quantum = depth_quantum(*s, f);
  if (quantum == 0.0) {
    EXPECT_EQ(integrity.checksum, reference.integrity.checksum) << what;
    test::expect_bit_identical_lists(reference.lists, lists, what);
  } else {
    const auto c = test::compare_within_quantum(reference.lists, lists, quantum);
    EXPECT_EQ(c.length_mismatches, 0u) << what;
    EXPECT_EQ(c.depth_mismatches, 0u) << what << ": max error " << c.max_error << ", quantum "
                                      << quantum;
  }
}

TEST_P(StructureConformance, ListsEqualPsppsllOnCornell) {
  expect_lists_equal_psppsll(structure(), "cornell", 8, 32);
}

TEST_P(StructureConformance, ListsEqualPsppsllOnAtrium) {
  expect_lists_equal_psppsll(structure(), "atrium", 12, 64);
}

TEST_P(StructureConformance, RepeatedBuildsGiveIdenticalChecksumsAndAreJudgedOk) {
  const LdmFixture f("atrium", 8, 32);
  const auto s = f.build(structure());
  const LdmInspector inspector(*s, *f.inputs);
  BuildHealth health(f.census);
  const LdmIntegrity first = inspector.check();
  health.observe(s->stats(), first);
  for (int i = 1; i < 5; ++i) {
    s->build(*f.inputs, nullptr);
    const LdmIntegrity again = inspector.check();
    EXPECT_EQ(again, first) << "build " << i;
    health.observe(s->stats(), again);
  }
  EXPECT_EQ(health.status(), BuildStatus::Ok) << health.detail();
  EXPECT_EQ(health.checksum_changes(), 0u);
}

TEST_P(StructureConformance, EveryStructureSaysHowItCanBeLossy) {
  EXPECT_TRUE(lossy_configurations().count(structure()))
      << "add " << structure() << " to lossy_configurations() in " << __FILE__;
}

TEST_P(StructureConformance, LossIsCountedExactlyAndJudgedLossy) {
  const auto entry = lossy_configurations().find(structure());
  ASSERT_NE(entry, lossy_configurations().end());
  const LdmFixture f("atrium", 8, 32);
  const std::optional<Params> params = entry->second(f.census);
  if (!params) GTEST_SKIP() << structure() << " has no capacity parameter";
  const auto reference = test::build_psppsll_reference(f);
  const auto s = f.build(structure(), *params);
  const BuildStats stats = s->stats();
  EXPECT_GT(stats.fragments_lost, 0u) << "the lossy configuration lost nothing";
  EXPECT_TRUE(stats.overflow) << "a lossy build must say so";
  EXPECT_EQ(stats.fragments_stored + stats.fragments_lost, f.census.total_fragments);
  const LdmIntegrity integrity = LdmInspector(*s, *f.inputs).check();
  EXPECT_EQ(integrity.fragments, stats.fragments_stored);
  EXPECT_EQ(integrity.unsorted_pixels, 0u);
  const auto lists = test::read_all_views(*s, f);
  EXPECT_EQ(test::missing_fragments(reference.lists, lists), int64_t(stats.fragments_lost));
  EXPECT_EQ(test::pixels_not_a_subsequence(reference.lists, lists, depth_quantum(*s, f)), 0u);
  BuildHealth health(f.census);
  health.observe(stats, integrity);
  EXPECT_EQ(health.status(), BuildStatus::Lossy) << health.detail();
}

// AO(x) = 2/N sum_i V(d_i) |cos theta_i| with V(d) = min(d / d_max, 1)^e: a depth read off
// by at most the quantum q moves V by at most e q / d_max per direction pair, so
// |AO - AO_PSPPSLL| <= 2 e q / d_max plus float rounding; 0 for exact depths.
TEST_P(StructureConformance, AoEqualsAoThroughPsppsll) {
  const LdmFixture f("cornell", 8, 32);
  ASSERT_TRUE(f.scene.ao.attenuated);
  const auto reference = f.build("psppsll");
  const auto s = f.build(structure());
  const Image expected = test::render_ao(*reference, f, 64);
  const Image actual = test::render_ao(*s, f, 64);
  ASSERT_TRUE(actual.same_shape(expected));
  const double q = depth_quantum(*s, f);
  const double tolerance =
      q == 0.0 ? 0.0 : 2 * f.scene.ao.falloff_exponent * q / f.scene.ao.d_max + 4 * 1.2e-7 * 2.0;
  uint64_t beyond = 0, shaded = 0;
  double max_difference = 0;
  for (size_t i = 0; i < expected.pixels.size(); ++i) {
    const double d = q == 0.0 ? double(test::float_bits(expected.pixels[i]) !=
                                       test::float_bits(actual.pixels[i]))
                              : std::abs(double(expected.pixels[i]) - double(actual.pixels[i]));
    max_difference = std::max(max_difference, d);
    beyond += d > tolerance;
    shaded += expected.pixels[i] > 0.0f;
  }
  EXPECT_GT(shaded, expected.pixels.size() / 4) << "the camera must see the scene";
  EXPECT_EQ(beyond, 0u) << "of " << expected.pixels.size() << " AO values; max difference "
                        << max_difference << ", tolerance " << tolerance;
}

TEST_P(StructureConformance, TheSharedMeasurementJudgesADefaultBuildOk) {
  MeasurementRequest request = test::measurement_request(structure(), 4, 16, 16, 1, 2);
  const Measurement m = measure(load_scene("cornell"), request);
  EXPECT_EQ(m.status(), BuildStatus::Ok) << m.status_detail();
  EXPECT_EQ(m.count(columns::kFragmentsStored), m.count(columns::kFragments));
  EXPECT_EQ(m.frames.size(), 2u);
}

// stats() and memory() each read back what they need: asked in any order, any number of
// times, after a build, they agree; memory() alone already knows what the build used.
TEST_P(StructureConformance, StatsAndMemoryAreSelfContained) {
  const LdmFixture f("cornell", 4, 16);
  const auto s = f.build(structure());
  const std::vector<BufferMemory> before = s->memory();  // no stats() call yet
  const BuildStats first = s->stats(), second = s->stats();
  const std::vector<BufferMemory> after = s->memory();
  EXPECT_EQ(first.fragments_stored, second.fragments_stored);
  EXPECT_EQ(first.fragments_lost, second.fragments_lost);
  EXPECT_EQ(first.counters, second.counters);
  ASSERT_EQ(before.size(), after.size());
  uint64_t used = 0, allocated = 0;
  for (size_t i = 0; i < before.size(); ++i) {
    EXPECT_EQ(before[i].name, after[i].name);
    EXPECT_EQ(before[i].allocated, after[i].allocated) << before[i].name;
    EXPECT_EQ(before[i].used, after[i].used) << before[i].name;
    EXPECT_LE(before[i].used, before[i].allocated) << before[i].name;
    used += before[i].used;
    allocated += before[i].allocated;
  }
  // Storage that holds every fragment's depth cannot be less than 4 bytes a fragment.
  EXPECT_GE(used, 4 * f.census.total_fragments);
  EXPECT_GT(allocated, 0u);
}

INSTANTIATE_TEST_SUITE_P(Registered, StructureConformance, ::testing::ValuesIn(structure_names()),
                         [](const auto& info) { return info.param; });

}  // namespace
}  // namespace ldm
