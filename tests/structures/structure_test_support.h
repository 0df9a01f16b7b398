#pragma once
// Checks shared by the post-sorted structures' tests (ppsll_test.cpp, dfbuffer_test.cpp):
// a structure built on the same scene and views as PSPPSLL must hold the same lists, bit
// for bit and in the same order, whichever sorting path it took.
#include <gtest/gtest.h>

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

// The default local array (the census's maximum depth complexity) sorts every list locally.
inline void expect_matches_psppsll(const std::string& structure, const std::string& scene,
                                   uint32_t n, uint32_t r) {
  const LdmFixture f(scene, n, r);
  ASSERT_GT(f.census.total_fragments, 0u);
  ASSERT_LE(f.census.max_depth_complexity, 128u) << "the default local array is capped at 128";
  const auto reference = build_psppsll_reference(f);
  expect_same_lists_as_psppsll(f, reference, structure, {}, f.census.max_depth_complexity);
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

// Five constructions into the same storage: the same lists each time, PSPPSLL's checksum.
inline void expect_repeated_builds_identical(const std::string& structure, const std::string& scene,
                                             uint32_t n, uint32_t r) {
  const LdmFixture f(scene, n, r);
  const auto reference = build_psppsll_reference(f);
  const auto s = f.build(structure);
  const LdmInspector inspector(*s, *f.inputs);
  for (int i = 0; i < 5; ++i) {
    if (i > 0) s->build(*f.inputs, nullptr);
    const BuildStats stats = s->stats();
    EXPECT_EQ(stats.fragments_stored, f.census.total_fragments) << "build " << i;
    EXPECT_EQ(stats.fragments_lost, 0u) << "build " << i;
    const LdmIntegrity integrity = inspector.check();
    EXPECT_EQ(integrity, reference.integrity) << "build " << i;
  }
}

// AO through `structure` and through PSPPSLL, 64 x 64 on the fixture's camera: the same
// lists through the same trace, so the same floats.
inline void expect_ao_identical_to_psppsll(const std::string& structure, const std::string& scene,
                                           uint32_t n, uint32_t r) {
  const LdmFixture f(scene, n, r);
  const auto reference = f.build("psppsll");
  const auto s = f.build(structure);
  const Image expected = render_ao(*reference, f, 64);
  const Image actual = render_ao(*s, f, 64);
  ASSERT_EQ(expected.pixels.size(), actual.pixels.size());
  uint64_t differing = 0, shaded = 0;
  for (size_t i = 0; i < expected.pixels.size(); ++i) {
    differing += float_bits(expected.pixels[i]) != float_bits(actual.pixels[i]);
    shaded += expected.pixels[i] > 0.0f;
  }
  EXPECT_GT(shaded, expected.pixels.size() / 4) << "the camera must see the scene";
  EXPECT_EQ(differing, 0u) << "of " << expected.pixels.size() << " AO values";
}

}  // namespace ldm::test
