#pragma once
// The sweep file of `ldmbench sweep` (docs/guide/sweeps.md): a JSON object naming axes whose
// cartesian product, plus "include" blocks, minus "exclude" filters, is the set of
// configurations. This unit only reads and checks the file and enumerates the combinations
// (each an assignment axis -> value); it knows the allowed names through a SweepVocabulary
// and nothing of GL, scenes or structures, so that it can be fuzzed alone
// (tests/fuzz/targets/fuzz_sweep.cpp). harness/run/sweep_plan.h turns combinations into
// configurations of `ldmbench run`.
//
// Every error names the file and the JSON path: `sweep.json: axes.structures[2]: unknown
// structure "foo" (known: ...)`.
#include <cstddef>
#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "harness/axes/axis.h"
#include "harness/settings/setting_rule.h"

namespace ldm {

// The axes a sweep file may name, as declared (harness/axes/axis.h); filled from the axis
// registry by the caller (harness/run/sweep_plan.h: current_sweep_vocabulary()).
struct SweepVocabulary {
  std::vector<AxisSpec> axes;                                // the harness's, canonical order
  std::map<std::string, std::vector<AxisSpec>> parameters;  // owner -> its parameters
  // The run-wide settings of the "settings" object, in their declared order
  // (harness/settings/run_setting_table.h: run_setting_rules()).
  std::vector<SettingRule> settings;
};

// One combination: axis name -> its value, canonical (names and WxH as strings, integers as
// unsigned JSON numbers, reals as doubles, booleans as booleans, parameter values as the
// canonical text --param would carry).
using SweepAssignment = std::map<std::string, nlohmann::json>;

struct SweepSpec {
  std::string name;  // the file name, prefix of every error
  std::string description;
  // The axes in canonical order (scenes, passes, structures, views, ..., OWNER:KEY sorted),
  // each with its values in the file's order ("all" structures expanded).
  std::vector<std::pair<std::string, std::vector<nlohmann::json>>> axes;
  // Each include block: axes whose values replace the main axes' (the others kept whole).
  std::vector<std::map<std::string, std::vector<nlohmann::json>>> include;
  // Each exclude filter: axis -> the values it matches (a combination matching every axis
  // of a filter is removed).
  std::vector<std::map<std::string, std::vector<nlohmann::json>>> exclude;
  nlohmann::json settings = nlohmann::json::object();  // checked; see sweep_plan.h
  std::string canonical;  // the parsed file dumped (sorted keys): identity of the sweep
  std::vector<std::string> axis_order;  // the vocabulary's axis keys, canonical order
  std::vector<std::string> warnings;  // e.g. an exclude filter that removes nothing
};

// Parses and checks `text`; throws UserError "<name>: <json path>: <what is wrong>".
SweepSpec parse_sweep_spec(const std::string& text, const std::string& name,
                           const SweepVocabulary& vocabulary);

// Combinations in a fixed order: the main product (first axis slowest), then each include
// block's product; minus those an exclude filter matches; duplicates dropped (first kept).
// Records in spec.warnings an exclude filter that matched nothing. Throws UserError when the
// product exceeds kMaxSweepCombinations.
inline constexpr size_t kMaxSweepCombinations = 100000;
std::vector<SweepAssignment> sweep_combinations(SweepSpec& spec);

}  // namespace ldm
