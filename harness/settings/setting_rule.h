#pragma once
// How a sweep file's run-wide setting is checked: plain data, made from the setting's
// declaration (harness/settings/run_setting_table.h: run_setting_rules()) and handed to the
// sweep file's parser (harness/run/sweep_spec.h: SweepVocabulary::settings), which knows
// nothing of RunSettings, so that it can be fuzzed alone.
#include <string>
#include <vector>

namespace ldm {

struct SettingRule {
  // Flag: true or false; Integer: an unsigned integer in [min, max]; Real: a number in
  // [min, max] (with `positive`: any finite number > 0); Choice: one of `choices`.
  enum class Kind { Flag, Integer, Real, Choice };
  // The key in the file's "settings" object, dotted: "timing.cap_s" is settings.timing.cap_s.
  std::string path;
  Kind kind = Kind::Flag;
  double min = 0, max = 0;
  bool positive = false;
  std::vector<std::string> choices;
};

}  // namespace ldm
