// The HA-buffer (thesis §3.2.13), what is its own (the properties every structure shares —
// lists equal PSPPSLL's within depth_quantum(), identical rebuilds, AO within the quantum's
// bound — are in conformance_test.cpp): the 32-bit quantum's size, 64-bit keys, the age cap
// and an under-sized table dropping fragments counted exactly, sizing.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "harness/util/error.h"
#include "structures/structure_test_support.h"

namespace ldm {
namespace {

using test::LdmFixture;
using test::ViewLists;

double habuffer_depth_quantum(const LdmStructure& s, const LdmFixture& f) {
  return s.depth_quantum(f.views.views[0]);
}

void expect_matches_psppsll(const std::string& scene, uint32_t n, uint32_t r,
                            const std::map<std::string, std::string>& params) {
  const LdmFixture f(scene, n, r);
  const auto reference = test::build_psppsll_reference(f);
  const auto ha = f.build("habuffer", params);
  const BuildStats stats = ha->stats();
  EXPECT_EQ(stats.fragments_lost, 0u);
  EXPECT_FALSE(stats.overflow);
  EXPECT_EQ(stats.fragments_stored, f.census.total_fragments);
  EXPECT_EQ(test::stats_counter(stats, "dropped_max_age"), 0.0);
  EXPECT_EQ(test::stats_counter(stats, "aborted_insertions"), 0.0);
  // Every pixel needs ages 0 .. n-1 at least.
  EXPECT_GE(test::stats_counter(stats, "max_age_used") + 1, double(f.census.max_depth_complexity));
  const double quantum = habuffer_depth_quantum(*ha, f);
  if (test::sizing_value(*ha, "key_bits") == "32") {
    // Half a power-of-two step no coarser than twice the 24-bit precision of the range.
    const double precision = f.views.views[0].depth_range / 16777215.0;
    EXPECT_GE(quantum, 0.5 * precision);
    EXPECT_LT(quantum, precision);
  } else {
    EXPECT_EQ(quantum, 0.0);
  }
  const LdmIntegrity integrity = LdmInspector(*ha, *f.inputs).check();
  EXPECT_EQ(integrity.fragments, f.census.total_fragments);
  EXPECT_EQ(integrity.unsorted_pixels, 0u);
  EXPECT_EQ(integrity.overlong_pixels, 0u);
  const test::QuantumComparison c =
      test::compare_within_quantum(reference.lists, test::read_all_views(*ha, f), quantum);
  EXPECT_EQ(c.length_mismatches, 0u);
  EXPECT_EQ(c.depth_mismatches, 0u) << "max error " << c.max_error << ", quantum " << quantum;
  std::printf(
      "habuffer on %s N=%u R=%u: %llu fragments, |H|=%s, key bits %s, max age used %g, "
      "max depth error %.3g (quantum %.3g)\n",
      scene.c_str(), n, r, (unsigned long long)f.census.total_fragments,
      test::sizing_value(*ha, "table_entries").c_str(), test::sizing_value(*ha, "key_bits").c_str(),
      test::stats_counter(stats, "max_age_used"), c.max_error, quantum);
}

TEST(HaBuffer, CornellMatchesPsppsllWithin32BitQuantum) {
  expect_matches_psppsll("cornell", 8, 32, {{"key_bits", "32"}});
}

// The default packing is the thesis's 32-bit key on every device, so that bytes and error
// do not change with the device; the record says which packing ran.
TEST(HaBuffer, DefaultKeysAre32BitsOnEveryDevice) {
  const LdmFixture f("cornell", 4, 32);
  const auto ha = f.prepare("habuffer");
  EXPECT_EQ(test::sizing_value(*ha, "key_bits"), "32");
  EXPECT_EQ(test::sizing_value(*ha, "key_bits_request"), "32");
  const auto automatic = f.prepare("habuffer", {{"key_bits", "auto"}});
  EXPECT_EQ(test::sizing_value(*automatic, "key_bits"),
            test::gl_context().device().has_int64_atomics ? "64" : "32");
}

// 64-bit keys: exact floats where the device has 64-bit atomics; a UserError naming the
// parameter where it does not.
TEST(HaBuffer, SixtyFourBitKeysNeedInt64Atomics) {
  const LdmFixture f("cornell", 8, 32);
  auto ha = make_structure("habuffer", test::params({{"key_bits", "64"}}));
  if (!test::gl_context().device().has_int64_atomics) {
    try {
      ha->prepare(*f.inputs);
      ADD_FAILURE() << "key_bits=64 accepted without GL_NV_shader_atomic_int64";
    } catch (const UserError& e) {
      EXPECT_NE(std::string(e.what()).find("key_bits=64"), std::string::npos) << e.what();
    }
    return;
  }
  ha->prepare(*f.inputs);
  ha->build(*f.inputs, nullptr);
  EXPECT_EQ(test::sizing_value(*ha, "key_bits"), "64");
  EXPECT_EQ(ha->stats().fragments_lost, 0u);
  const auto reference = test::build_psppsll_reference(f);
  const test::QuantumComparison c =
      test::compare_within_quantum(reference.lists, test::read_all_views(*ha, f), 0.0);
  EXPECT_EQ(c.length_mismatches, 0u);
  EXPECT_EQ(c.depth_mismatches, 0u) << "64-bit keys store the float itself";
}

// A lossy build: fragments_lost must be exactly what read_back misses against PSPPSLL, every
// kept list the pixel's own fragments in order, and the build flagged.
void expect_exact_loss(const LdmFixture& f, const test::PsppsllReference& reference,
                       const std::map<std::string, std::string>& params,
                       uint64_t fewest_possible_losses) {
  const auto ha = f.build("habuffer", params);
  const BuildStats stats = ha->stats();
  ASSERT_GT(fewest_possible_losses, 0u) << "this configuration cannot lose fragments";
  EXPECT_GE(stats.fragments_lost, fewest_possible_losses);
  EXPECT_TRUE(stats.overflow);
  EXPECT_EQ(stats.fragments_stored + stats.fragments_lost, f.census.total_fragments);
  EXPECT_EQ(test::stats_counter(stats, "aborted_insertions"), 0.0);
  EXPECT_EQ(test::stats_counter(stats, "dropped_max_age"), double(stats.fragments_lost));
  const auto lists = test::read_all_views(*ha, f);
  EXPECT_EQ(test::missing_fragments(reference.lists, lists), int64_t(stats.fragments_lost));
  const LdmIntegrity integrity = LdmInspector(*ha, *f.inputs).check();
  EXPECT_EQ(integrity.fragments, stats.fragments_stored);
  EXPECT_EQ(integrity.unsorted_pixels, 0u);
  EXPECT_EQ(test::pixels_not_a_subsequence(reference.lists, lists, habuffer_depth_quantum(*ha, f)), 0u);
  std::printf(
      "habuffer lossy (%s): lost %llu of %llu (at least %llu)\n",
      [&] {
        std::string s;
        for (const auto& [k, v] : params) s += k + "=" + v + " ";
        return s;
      }()
          .c_str(),
      (unsigned long long)stats.fragments_lost, (unsigned long long)f.census.total_fragments,
      (unsigned long long)fewest_possible_losses);
}

TEST(HaBuffer, SmallMaxAgeDropsAreCountedExactly) {
  const LdmFixture f("atrium", 12, 64);
  const auto reference = test::build_psppsll_reference(f);
  const uint32_t max_age = f.census.max_depth_complexity / 2;
  // A pixel holds at most one entry per age: ages 0..max_age hold max_age + 1 of its fragments.
  expect_exact_loss(f, reference, {{"max_age", std::to_string(max_age)}},
                    f.census.fragments_beyond(max_age + 1));
}

TEST(HaBuffer, OneSlotPerPixelTableDropsAreCountedExactly) {
  const LdmFixture f("atrium", 12, 64);
  const auto reference = test::build_psppsll_reference(f);
  // A load factor far above 1 sizes |H| to its age-equivalence minimum, N * R_LDM^2.
  const uint64_t slots = f.views.total_pixels();
  const uint64_t fragments = f.census.total_fragments;
  expect_exact_loss(f, reference, {{"load_factor", "64"}, {"max_age", "32"}},
                    fragments > slots ? fragments - slots : 0);
}

TEST(HaBuffer, SizingFollowsTheCensusAndTheAgeEquivalenceBound) {
  const LdmFixture f("cornell", 8, 32);
  const uint64_t pixels = f.views.total_pixels();
  const auto ha = f.build("habuffer", {{"load_factor", "0.5"}, {"max_age", "100"}});
  const uint64_t table = std::stoull(test::sizing_value(*ha, "table_entries"));
  EXPECT_EQ(table, std::max<uint64_t>(pixels, 2 * f.census.total_fragments));
  EXPECT_EQ(test::sizing_value(*ha, "max_age"), "100");
  const auto packed = f.build("habuffer", {{"load_factor", "64"}});
  EXPECT_EQ(std::stoull(test::sizing_value(*packed, "table_entries")), pixels);
  const uint64_t key_bytes = std::stoull(test::sizing_value(*ha, "key_bits")) / 8;
  bool saw_table = false, saw_age_table = false;
  for (const BufferMemory& m : ha->memory()) {
    if (m.name == "table") saw_table = m.allocated == table * key_bytes;
    if (m.name == "age_table") saw_age_table = m.allocated == pixels * sizeof(uint32_t);
  }
  EXPECT_TRUE(saw_table);
  EXPECT_TRUE(saw_age_table);
}

TEST(HaBuffer, OutOfRangeParametersAreUserErrors) {
  test::expect_params_checked("habuffer", {{{"max_age", "255"}}, {{"key_bits", "48"}}, {{"load_factor", "0"}}});
}

}  // namespace
}  // namespace ldm
