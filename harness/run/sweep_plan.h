#pragma once
// A sweep file (harness/run/sweep_spec.h) as the configurations of `ldmbench run`: every
// combination becomes a RunSettings with one value per axis, expanded by the same
// expand_configurations() and checked by the same validate_axes() as a command line, so a
// sweep measures nothing `ldmbench run` would not. Combinations that differ only in axes a
// configuration does not use (N for the HBAO peer, ppfla:k for psppsll) are one
// configuration. Everything is checked before any GPU work: errors name the file and the
// JSON path or the combination.
#include <map>
#include <string>
#include <vector>

#include "harness/run/run_command.h"
#include "harness/run/sweep_spec.h"

namespace ldm {

// --shard i/n: slice i of n, interleaved and balanced along every axis
// (harness/run/shard_assignment.h, docs/guide/sweeps.md).
struct Shard {
  size_t index = 0, count = 1;
  std::string text() const { return std::to_string(index) + "/" + std::to_string(count); }
};
Shard parse_shard(const std::string& text);  // "i/n", 0 <= i < n; throws UserError

struct SweepPlan {
  SweepSpec spec;
  std::string path;
  size_t combinations = 0;  // after include/exclude, before merging equal configurations
  std::vector<PlannedConfiguration> configurations;  // the whole sweep, in order
  std::map<std::string, Scene> scenes;               // every scene the sweep names, loaded
  std::string sweep_hash;  // the file's parsed content: equal for equal sweeps
};

// The vocabulary of this build (structures, passes, traces, estimators).
SweepVocabulary current_sweep_vocabulary();

// Reads, checks and expands the sweep file. `base` supplies what the file does not set
// (cache folder, EGL options). Throws UserError "<file>: <where>: <what>".
SweepPlan plan_sweep(const std::string& path, const RunSettings& base);

// The indices (into plan.configurations, ascending) of the configurations `shard` measures:
// assign_shards() over their axis values. Every shard of a plan gets a disjoint part, and
// together they are the whole plan.
std::vector<size_t> shard_members(const SweepPlan& plan, const Shard& shard);

}  // namespace ldm
