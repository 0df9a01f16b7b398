// Shards of a sweep (harness/run/shard_assignment.h): a partition of the configurations,
// sizes within one of each other, every axis value spread over the shards within one, also
// when the fastest axis has as many values as there are shards (where k mod n put all N=4 in
// shard 0 and all N=8 in shard 1); deterministic.
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "harness/run/shard_assignment.h"
#include "harness/run/sweep_plan.h"

namespace ldm {
namespace {

using Values = std::map<std::string, std::string>;

// The full product of axes "a0", "a1", ... with sizes[i] values each, the last axis fastest
// (a sweep file's order).
std::vector<Values> product(const std::vector<size_t>& sizes) {
  std::vector<Values> out(1);
  for (size_t axis = 0; axis < sizes.size(); ++axis) {
    std::vector<Values> next;
    for (const Values& partial : out)
      for (size_t v = 0; v < sizes[axis]; ++v) {
        Values values = partial;
        values["a" + std::to_string(axis)] = std::to_string(v);
        next.push_back(values);
      }
    out = next;
  }
  return out;
}

// The largest difference between two shards in how many configurations they hold, overall
// and with any one value of any one axis.
size_t worst_imbalance(const std::vector<Values>& configurations, const std::vector<size_t>& shard_of,
                       size_t shards) {
  std::map<std::string, std::vector<size_t>> counts;  // "" = size; "axis=value"
  for (size_t k = 0; k < configurations.size(); ++k) {
    auto& size = counts[""];
    size.resize(shards);
    ++size[shard_of[k]];
    for (const auto& [axis, value] : configurations[k]) {
      auto& c = counts[axis + "=" + value];
      c.resize(shards);
      ++c[shard_of[k]];
    }
  }
  size_t worst = 0;
  for (const auto& [key, c] : counts)
    worst = std::max(worst, *std::max_element(c.begin(), c.end()) - *std::min_element(c.begin(), c.end()));
  return worst;
}

std::vector<size_t> round_robin(size_t configurations, size_t shards) {
  std::vector<size_t> out;
  for (size_t k = 0; k < configurations; ++k) out.push_back(k % shards);
  return out;
}

TEST(ShardAssignment, FastestAxisWithAsManyValuesAsShardsIsSplit) {
  // Four structures x N in {4, 8}, N fastest, two shards: the case of issue 23.
  std::vector<Values> sweep;
  for (const char* structure : {"psppsll", "habuffer", "ppfla", "psppfla"})
    for (const char* n : {"4", "8"}) sweep.push_back({{"structures", structure}, {"views", n}});
  // The check can fail: k mod 2 gives shard 0 every N=4 (imbalance 4).
  EXPECT_EQ(worst_imbalance(sweep, round_robin(sweep.size(), 2), 2), 4u);
  const std::vector<size_t> shard_of = assign_shards(sweep, 2);
  EXPECT_EQ(worst_imbalance(sweep, shard_of, 2), 0u);
  for (size_t shard = 0; shard < 2; ++shard) {
    std::map<std::string, int> views, structures;
    for (size_t k = 0; k < sweep.size(); ++k)
      if (shard_of[k] == shard) ++views[sweep[k].at("views")], ++structures[sweep[k].at("structures")];
    EXPECT_EQ(views, (std::map<std::string, int>{{"4", 2}, {"8", 2}})) << "shard " << shard;
    EXPECT_EQ(structures.size(), 4u) << "shard " << shard;
  }
}

TEST(ShardAssignment, EveryValueSpreadWithinOneInSmallProducts) {
  std::vector<std::pair<std::vector<size_t>, size_t>> cases;  // axis sizes, shards
  for (size_t a = 1; a <= 5; ++a)
    for (size_t b = 1; b <= 5; ++b)
      for (size_t c = 1; c <= 5; ++c)
        for (size_t n = 2; n <= 6; ++n) cases.push_back({{a, b, c}, n});
  for (size_t a = 1; a <= 3; ++a)
    for (size_t b = 1; b <= 3; ++b)
      for (size_t c = 1; c <= 3; ++c)
        for (size_t d = 1; d <= 3; ++d)
          for (size_t n = 2; n <= 5; ++n) cases.push_back({{a, b, c, d}, n});
  size_t round_robin_unbalanced = 0;
  for (const auto& [sizes, shards] : cases) {
    const std::vector<Values> sweep = product(sizes);
    if (sweep.size() < shards) continue;
    const std::vector<size_t> shard_of = assign_shards(sweep, shards);
    ASSERT_EQ(shard_of.size(), sweep.size());
    for (size_t s : shard_of) ASSERT_LT(s, shards);
    std::string name;
    for (size_t size : sizes) name += std::to_string(size) + "x";
    EXPECT_LE(worst_imbalance(sweep, shard_of, shards), 1u) << name << " over " << shards << " shards";
    round_robin_unbalanced += worst_imbalance(sweep, round_robin(sweep.size(), shards), shards) > 1;
  }
  EXPECT_GT(round_robin_unbalanced, 100u);  // what the assignment is for
}

TEST(ShardAssignment, IsAFunctionOfTheValuesAndTheCount) {
  std::vector<Values> sweep = product({3, 4, 2});
  // Not a product: an include block's extra values, a configuration without an axis.
  sweep.push_back({{"a0", "9"}, {"a1", "0"}});
  sweep.push_back({{"a0", "9"}, {"a1", "1"}, {"a2", "1"}});
  const std::vector<size_t> first = assign_shards(sweep, 4);
  EXPECT_EQ(assign_shards(sweep, 4), first);
  EXPECT_LE(worst_imbalance({sweep.begin(), sweep.end()}, first, 4), 2u);
  std::vector<size_t> sizes(4);
  for (size_t s : first) ++sizes[s];
  EXPECT_LE(*std::max_element(sizes.begin(), sizes.end()) - *std::min_element(sizes.begin(), sizes.end()), 1u);
  EXPECT_EQ(assign_shards(sweep, 1), std::vector<size_t>(sweep.size(), 0));
  // More shards than configurations: some shards are empty, none holds two.
  const std::vector<size_t> sparse = assign_shards(product({3}), 5);
  EXPECT_EQ(std::set<size_t>(sparse.begin(), sparse.end()).size(), 3u);
}

TEST(ShardAssignment, ShardsOfAPlanPartitionIt) {
  // The Slurm CI step's sweep (N fastest, two values) through plan_sweep: each of two shards
  // measures both N; the shards together are the plan, once each.
  const SweepPlan plan = plan_sweep(std::string(LDM_TEST_SOURCE_DIR) + "/../sweeps/slurm-ci.json", RunSettings{});
  std::vector<size_t> seen;
  for (size_t i = 0; i < 2; ++i) {
    std::set<uint32_t> views;
    for (size_t k : shard_members(plan, Shard{i, 2})) {
      seen.push_back(k);
      views.insert(plan.configurations[k].config.views);
    }
    EXPECT_EQ(views, (std::set<uint32_t>{4, 8})) << "shard " << i;
  }
  std::sort(seen.begin(), seen.end());
  std::vector<size_t> all(plan.configurations.size());
  for (size_t k = 0; k < all.size(); ++k) all[k] = k;
  EXPECT_EQ(seen, all);
}

}  // namespace
}  // namespace ldm
