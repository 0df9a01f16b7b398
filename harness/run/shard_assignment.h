#pragma once
// Which shard of a sweep (`ldmbench sweep --shard i/n`) measures each configuration: every
// shard gets as many configurations as any other (one more at most) and, as far as the
// search below finds, the same mix along every axis, so that no shard holds all of one
// value (all N=4 on one node, all N=8 on another would confound N with the node, and a lost
// shard would lose a whole value).
//
// How (fixed, deterministic: a function of the configurations' axis values, their order and
// the shard count only; docs/guide/sweeps.md#shards-merge-and-slurm): two deals of the list,
// each balanced in size, are improved by swapping configurations between shards while a swap
// lowers the sum over axis values and shards of (configurations with that value in that
// shard)^2 (within a fixed number of swaps tried, which only sweeps of many thousand
// configurations reach); the deal with the lower sum is kept (the first on a tie). The deals: round robin
// (k mod n) and the digit sum (floor(k/n) + floor(k/n^2) + ... + k) mod n. In every full
// product of 3 axes of 1-5 values (2-6 shards) and of 4 axes of 1-3 values (2-5 shards) each
// value's count differs by at most one between shards (tests/sweep/shard_assignment_test.cpp).
#include <cstddef>
#include <map>
#include <string>
#include <vector>

namespace ldm {

// The shard (0 <= s < shards) of each configuration, given each one's axis values (axis key
// -> value; an axis missing from a configuration counts as its own value) in sweep order.
std::vector<size_t> assign_shards(const std::vector<std::map<std::string, std::string>>& configurations,
                                  size_t shards);

}  // namespace ldm
