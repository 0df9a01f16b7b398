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
  test::expect_fixed_pool_overflow_counted(LdmFixture("atrium", 8, 32), "ppsll");
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
  test::expect_params_checked(
      "ppsll", {{{"local", "0"}}, {{"local", "129"}}, {{"pool", "fixed"}}, {{"capacity", "0"}}, {{"locl", "4"}}},
      {{{"local", "128"}}});
}

}  // namespace
}  // namespace ldm
