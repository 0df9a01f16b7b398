#pragma once
// The run-wide settings (one value for the whole run, not an axis: the timing protocol, the
// sub-pass timer, build verification, the reference, images, the work replay), each declared
// once in run_setting_table.cpp with its field of RunSettings, its key in a sweep file's
// "settings" object, its `ldmbench run` option and help, its range or choices, and its record
// column where it has one. Everything else loops over the table:
//   - the options of `ldmbench run` and `ldmbench view` (harness/cli/run_options.cpp),
//   - the checks of a sweep file's settings and their "known:" lists (harness/run/sweep_spec.cpp,
//     through SweepVocabulary::settings, so that the parser stays free of RunSettings),
//   - reading them into RunSettings (harness/run/sweep_plan.cpp),
//   - writing them back as a command line and as a sweep file (run_command_line.cpp),
//   - the record columns time_target, time_cap_s, time_clock_warmup_s
//     (harness/measuring/timing_columns.cpp).
// A new run-wide setting is its declaration here and its consumer, nothing else.
#include <cstdint>
#include <string>
#include <variant>
#include <vector>

#include <nlohmann/json.hpp>

#include "harness/records/columns.h"
#include "harness/settings/setting_rule.h"
#include "harness/settings/run_settings.h"

namespace ldm {

// A field of RunSettings, as a function returning a reference to it (nested fields:
// reference.spp.spp_per_half); a captureless lambda converts to one.
template <typename T>
using SettingFieldOf = T& (*)(RunSettings&);
// A setting stored as an enum: its text and how to store a text (checked against choices).
struct SettingText {
  std::string (*get)(const RunSettings&);
  void (*set)(RunSettings&, const std::string&);
};
// Where a setting lives: a field of RunSettings, its text, or a field of the timing precision
// (RunSettings::precision), which a measurement's TimingOutcome carries to its record.
using SettingField = std::variant<SettingFieldOf<bool>, SettingFieldOf<int>, SettingFieldOf<uint32_t>,
                                  SettingFieldOf<uint64_t>, SettingFieldOf<double>,
                                  SettingFieldOf<std::string>, SettingText, double TimePrecision::*>;

struct RunSetting {
  // The key in a sweep file's "settings" object, dotted: "timing.cap_s" is
  // settings.timing.cap_s, "images" is settings.images.
  std::string path;
  // The `ldmbench run` option. A flag (bool) is on by default and its option turns it off
  // (--no-images).
  std::string flag;
  std::string help;
  SettingRule::Kind kind = SettingRule::Kind::Flag;
  SettingField field;
  // Integer, Real: the accepted range, inclusive; a Real with `positive` accepts any finite
  // number > 0 instead.
  double min = 0, max = 0;
  bool positive = false;
  // Whether the command line checks the range too (the reference seed is a 64-bit option that
  // a sweep file limits to 32 bits).
  bool cli_range = true;
  std::vector<std::string> choices;  // Choice
  // The record column that carries the setting (a field of the precision only), or null.
  const Column* column = nullptr;
  // Written to a command line or a sweep file only while this flag setting is on (the
  // reference's settings, with the reference enabled); empty: always.
  std::string written_when;

  // The sweep-file key's parts: "timing.cap_s" -> "timing", "cap_s"; "images" -> "", "images".
  std::string group() const;
  std::string key() const;
};

// Every run-wide setting, in the order a command line and a sweep file write them.
const std::vector<RunSetting>& run_setting_table();
const RunSetting* find_run_setting(const std::string& path);

// The setting's value in `settings`: as JSON (a sweep file's type), as a command-line word.
nlohmann::json run_setting_json(const RunSetting& setting, const RunSettings& settings);
std::string run_setting_text(const RunSetting& setting, const RunSettings& settings);
// Stores a value already checked by its rule (sweep_spec's check of the file).
void set_run_setting_json(const RunSetting& setting, RunSettings& settings, const nlohmann::json& value);
// Whether the setting is written for these settings (its written_when flag is on).
bool run_setting_written(const RunSetting& setting, const RunSettings& settings);

// The rules a sweep file's settings are checked by (SweepVocabulary::settings).
std::vector<SettingRule> run_setting_rules();

// The shortest text that reads back as the same double (0.03, not 0.029999999999999999).
std::string shortest_number_text(double value);

}  // namespace ldm
