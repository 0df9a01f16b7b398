#pragma once
// Checks shared by the structure tests (conformance_test.cpp and the per-structure files):
// a structure built on the same scene and views as PSPPSLL must hold the same lists, bit
// for bit and in the same order (or within its depth quantum), whichever path it took.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <map>
#include <string>

#include "structures/psppsll_reference.h"

namespace ldm::test {

using Params = std::map<std::string, std::string>;

inline uint32_t float_bits(float f) {
  uint32_t u;
  std::memcpy(&u, &f, sizeof u);
  return u;
}

// Pixels whose fragments exceed the sort's local array of k: those the sort pass must
// sort in place.
inline uint64_t pixels_longer_than(const FragmentCensus& census, uint32_t k) {
  uint64_t pixels = 0;
  for (uint32_t n : census.counts) pixels += n > k;
  return pixels;
}

// Lists equal entry by entry, compared as bits (float == would forgive -0.0 vs 0.0).
inline void expect_bit_identical_lists(const std::vector<ViewLists>& expected,
                                       const std::vector<ViewLists>& actual,
                                       const std::string& what) {
  ASSERT_EQ(expected.size(), actual.size()) << what;
  uint64_t differing_pixels = 0;
  for (size_t v = 0; v < expected.size(); ++v) {
    ASSERT_EQ(expected[v].size(), actual[v].size()) << what << ": view " << v;
    for (size_t p = 0; p < expected[v].size(); ++p) {
      const auto& e = expected[v][p];
      const auto& a = actual[v][p];
      bool same = e.size() == a.size();
      for (size_t i = 0; same && i < e.size(); ++i) same = float_bits(e[i]) == float_bits(a[i]);
      if (!same && ++differing_pixels <= 3)
        ADD_FAILURE() << what << ": view " << v << " pixel " << p << " holds " << a.size()
                      << " depths, PSPPSLL " << e.size() << " (or the depths differ)";
    }
  }
  EXPECT_EQ(differing_pixels, 0u) << what;
}

struct QuantumComparison {
  uint64_t length_mismatches = 0;  // pixels whose list length differs from PSPPSLL's
  uint64_t depth_mismatches = 0;   // depths farther than the quantum from PSPPSLL's
  double max_error = 0;
};

// Entry i of every pixel against PSPPSLL's entry i: both lists are sorted, and quantising is
// monotonic, so the orders agree and each depth is within the quantum of its counterpart.
inline QuantumComparison compare_within_quantum(const std::vector<ViewLists>& reference,
                                         const std::vector<ViewLists>& lists, double quantum) {
  QuantumComparison c;
  for (size_t v = 0; v < reference.size(); ++v)
    for (size_t p = 0; p < reference[v].size(); ++p) {
      const auto& e = reference[v][p];
      const auto& a = lists[v][p];
      if (e.size() != a.size()) {
        ++c.length_mismatches;
        continue;
      }
      for (size_t i = 0; i < e.size(); ++i) {
        const double error = std::abs(double(a[i]) - double(e[i]));
        c.max_error = std::max(c.max_error, error);
        c.depth_mismatches += error > quantum;
      }
    }
  return c;
}

// A lossy list must still be the pixel's own fragments in order: a subsequence of PSPPSLL's
// list, entry by entry within the quantum (greedy matching is exact for sorted lists).
inline uint64_t pixels_not_a_subsequence(const std::vector<ViewLists>& reference,
                                  const std::vector<ViewLists>& lists, double quantum) {
  uint64_t bad = 0;
  for (size_t v = 0; v < reference.size(); ++v)
    for (size_t p = 0; p < reference[v].size(); ++p) {
      const auto& e = reference[v][p];
      size_t j = 0;
      bool ok = true;
      for (float d : lists[v][p]) {
        while (j < e.size() && std::abs(double(e[j]) - double(d)) > quantum) ++j;
        if (j == e.size()) {
          ok = false;
          break;
        }
        ++j;
      }
      bad += !ok;
    }
  return bad;
}

// Builds `structure` with `params` on the fixture and checks it against PSPPSLL: every
// fragment stored, none lost, lists sorted and bit-identical, the in-place count exact.
inline void expect_same_lists_as_psppsll(const LdmFixture& f, const PsppsllReference& reference,
                                         const std::string& structure, const Params& params,
                                         uint32_t local) {
  const std::string what = structure + " (local " + std::to_string(local) + ")";
  const auto s = f.build(structure, params);
  const BuildStats stats = s->stats();
  EXPECT_EQ(stats.fragments_rasterized, f.census.total_fragments) << what;
  EXPECT_EQ(stats.fragments_stored, f.census.total_fragments) << what;
  EXPECT_EQ(stats.fragments_lost, 0u) << what;
  EXPECT_FALSE(stats.overflow) << what;
  EXPECT_EQ(stats_counter(stats, "lists_sorted_in_place"),
            double(pixels_longer_than(f.census, local)))
      << what;
  EXPECT_EQ(sizing_value(*s, "sort_local"), std::to_string(local)) << what;
  const LdmIntegrity integrity = LdmInspector(*s, *f.inputs).check();
  EXPECT_EQ(integrity.fragments, f.census.total_fragments) << what;
  EXPECT_EQ(integrity.unsorted_pixels, 0u) << what;
  EXPECT_EQ(integrity.overlong_pixels, 0u) << what;
  EXPECT_EQ(integrity.checksum, reference.integrity.checksum) << what;
  expect_bit_identical_lists(reference.lists, read_all_views(*s, f), what);
}

// Local arrays smaller than the longest lists force the in-place path on some pixels (on
// nearly all with local=1): the lists must come out the same.
inline void expect_in_place_sort_matches_psppsll(const std::string& structure,
                                                 const std::string& scene, uint32_t n, uint32_t r) {
  const LdmFixture f(scene, n, r);
  ASSERT_GE(f.census.max_depth_complexity, 3u) << "the scene must have lists to sort";
  const auto reference = build_psppsll_reference(f);
  for (uint32_t local : {1u, 2u, f.census.max_depth_complexity - 1}) {
    ASSERT_GT(pixels_longer_than(f.census, local), 0u);
    expect_same_lists_as_psppsll(f, reference, structure, {{"local", std::to_string(local)}},
                                 local);
  }
}

}  // namespace ldm::test
