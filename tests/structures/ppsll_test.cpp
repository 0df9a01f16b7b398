// PPSLL (thesis §3.2.8, §3.4.1) against PSPPSLL on the same scene and views: push_front
// construction plus the post-sort must give PSPPSLL's lists bit for bit, through the local
// array and through the in-place path alike, and lose nothing unless the pool is too small,
// in which case the loss is counted exactly.
#include <gtest/gtest.h>

#include "harness/util/error.h"
#include "structures/structure_test_support.h"

namespace ldm {
namespace {

using test::LdmFixture;

TEST(Ppsll, SmallLocalArraysSortInPlaceAndCountIt) {
  test::expect_in_place_sort_matches_psppsll("ppsll", "cornell", 8, 32);
  test::expect_in_place_sort_matches_psppsll("ppsll", "atrium", 8, 32);
}

TEST(Ppsll, FixedPoolOverflowIsCountedAndTheStoredListsAreSorted) {
  const LdmFixture f("atrium", 8, 32);
  const uint64_t capacity = f.census.total_fragments / 2;
  const auto s = f.build("ppsll", {{"capacity", std::to_string(capacity)}});
  const BuildStats stats = s->stats();
  EXPECT_TRUE(stats.overflow);
  EXPECT_EQ(stats.fragments_rasterized, f.census.total_fragments);
  EXPECT_EQ(stats.fragments_stored, capacity);
  EXPECT_EQ(stats.fragments_lost, f.census.total_fragments - capacity);
  const LdmIntegrity integrity = LdmInspector(*s, *f.inputs).check();
  EXPECT_EQ(integrity.fragments, capacity);
  EXPECT_EQ(integrity.unsorted_pixels, 0u);
}

TEST(Ppsll, MemoryAndSizingFollowTheCensus) {
  const LdmFixture f("cornell", 8, 32);
  const auto s = f.build("ppsll");
  EXPECT_EQ(test::sizing_value(*s, "pool_size_source"), "oracle");
  EXPECT_EQ(test::sizing_value(*s, "pool_capacity_nodes"),
            std::to_string(f.census.total_fragments));
  EXPECT_EQ(test::sizing_value(*s, "sort_local_policy"), "oracle_max_depth_complexity");
  bool found_nodes = false;
  for (const BufferMemory& m : s->memory()) {
    if (m.name == "heads") {
      EXPECT_EQ(m.allocated, f.census.total_pixels * 4);
    }
    if (m.name != "nodes") continue;
    found_nodes = true;
    EXPECT_EQ(m.allocated, f.census.total_fragments * 8);
    EXPECT_EQ(m.used, f.census.total_fragments * 8);
  }
  EXPECT_TRUE(found_nodes);
}

TEST(Ppsll, OutOfRangeParametersAreUserErrors) {
  test::gl_context();
  EXPECT_THROW(make_structure("ppsll", test::params({{"local", "0"}})), UserError);
  EXPECT_THROW(make_structure("ppsll", test::params({{"local", "129"}})), UserError);
  EXPECT_THROW(make_structure("ppsll", test::params({{"pool", "fixed"}})), UserError);
  EXPECT_THROW(make_structure("ppsll", test::params({{"capacity", "0"}})), UserError);
  EXPECT_THROW(make_structure("ppsll", test::params({{"locl", "4"}})), UserError);
  EXPECT_NO_THROW(make_structure("ppsll", test::params({{"local", "128"}})));
}

}  // namespace
}  // namespace ldm
