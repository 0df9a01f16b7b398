#include "harness/run/shard_assignment.h"

#include <cstdint>
#include <set>

namespace ldm {
namespace {

// Configuration k's values as small integers over the axes that vary (an axis with one value
// everywhere changes no count that a swap could move).
std::vector<std::vector<uint32_t>> value_ids(const std::vector<std::map<std::string, std::string>>& configurations,
                                             size_t& value_count) {
  std::set<std::string> axes;
  for (const auto& values : configurations)
    for (const auto& [axis, value] : values) axes.insert(axis);
  std::vector<std::vector<uint32_t>> ids(configurations.size());
  value_count = 0;
  for (const std::string& axis : axes) {
    std::map<std::string, uint32_t> seen;  // "" stands for the axis missing: keys are "=" + value
    std::vector<uint32_t> column;
    for (const auto& values : configurations) {
      const auto it = values.find(axis);
      const std::string key = it == values.end() ? std::string() : "=" + it->second;
      column.push_back(seen.emplace(key, uint32_t(value_count + seen.size())).first->second);
    }
    if (seen.size() < 2) continue;
    value_count += seen.size();
    for (size_t k = 0; k < configurations.size(); ++k) ids[k].push_back(column[k]);
  }
  return ids;
}

// One deal and its counts: count[value * shards + shard].
class Deal {
 public:
  Deal(const std::vector<std::vector<uint32_t>>& ids, size_t value_count, size_t shards, std::vector<size_t> shard_of)
      : ids_(ids), shards_(shards), shard_of_(std::move(shard_of)), count_(value_count * shards, 0) {
    for (size_t k = 0; k < ids_.size(); ++k)
      for (uint32_t v : ids_[k]) ++at(v, shard_of_[k]);
  }

  // Swaps while a swap lowers the sum of squared counts (it strictly decreases: this ends),
  // trying pairs in order, at most `budget` of them: a count, not a time, so that every
  // shard's process computes the same deal. Sweeps of a few thousand configurations finish
  // well within it (about a second); a larger one keeps the best deal found.
  void improve(uint64_t budget) {
    for (bool improved = true; improved;) {
      improved = false;
      for (size_t i = 0; i < ids_.size(); ++i)
        for (size_t j = i + 1; j < ids_.size(); ++j) {
          if (shard_of_[i] == shard_of_[j]) continue;
          if (budget-- == 0) return;
          if (swap_change(i, j) < 0) {
            swap(i, j);
            improved = true;
          }
        }
    }
  }

  int64_t sum_of_squares() const {
    int64_t sum = 0;
    for (int64_t c : count_) sum += c * c;
    return sum;
  }
  const std::vector<size_t>& shard_of() const { return shard_of_; }

 private:
  int64_t& at(uint32_t value, size_t shard) { return count_[value * shards_ + shard]; }
  int64_t at(uint32_t value, size_t shard) const { return count_[value * shards_ + shard]; }

  // The change of the sum of squares if configurations i and j traded shards.
  int64_t swap_change(size_t i, size_t j) const {
    const size_t a = shard_of_[i], b = shard_of_[j];
    int64_t change = 0;
    for (size_t axis = 0; axis < ids_[i].size(); ++axis) {
      const uint32_t vi = ids_[i][axis], vj = ids_[j][axis];
      if (vi == vj) continue;
      // vi leaves a for b, vj leaves b for a: (c-1)^2 - c^2 = 1 - 2c, (c+1)^2 - c^2 = 1 + 2c.
      change += (1 - 2 * at(vi, a)) + (1 + 2 * at(vi, b)) + (1 - 2 * at(vj, b)) + (1 + 2 * at(vj, a));
    }
    return change;
  }

  void swap(size_t i, size_t j) {
    const size_t a = shard_of_[i], b = shard_of_[j];
    for (uint32_t v : ids_[i]) --at(v, a), ++at(v, b);
    for (uint32_t v : ids_[j]) --at(v, b), ++at(v, a);
    std::swap(shard_of_[i], shard_of_[j]);
  }

  const std::vector<std::vector<uint32_t>>& ids_;
  size_t shards_;
  std::vector<size_t> shard_of_;
  std::vector<int64_t> count_;
};

// Both deal every n consecutive configurations to n different shards (sizes balanced).
std::vector<size_t> round_robin(size_t configurations, size_t shards) {
  std::vector<size_t> out(configurations);
  for (size_t k = 0; k < configurations; ++k) out[k] = k % shards;
  return out;
}

std::vector<size_t> digit_sum(size_t configurations, size_t shards) {
  std::vector<size_t> out(configurations);
  for (size_t k = 0; k < configurations; ++k) {
    size_t sum = 0;
    for (size_t q = k; q; q /= shards) sum += q;
    out[k] = sum % shards;
  }
  return out;
}

}  // namespace

std::vector<size_t> assign_shards(const std::vector<std::map<std::string, std::string>>& configurations,
                                  size_t shards) {
  if (shards <= 1) return std::vector<size_t>(configurations.size(), 0);
  size_t value_count = 0;
  const auto ids = value_ids(configurations, value_count);
  constexpr uint64_t kSwapsTried = 50'000'000;  // per deal
  Deal best(ids, value_count, shards, round_robin(configurations.size(), shards));
  best.improve(kSwapsTried);
  Deal other(ids, value_count, shards, digit_sum(configurations.size(), shards));
  other.improve(kSwapsTried);
  return other.sum_of_squares() < best.sum_of_squares() ? other.shard_of() : best.shard_of();
}

}  // namespace ldm
