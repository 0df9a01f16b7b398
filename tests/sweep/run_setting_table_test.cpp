// The run-wide settings declared once (harness/settings/run_setting_table.h): walking the
// table, every setting travels sweep file -> RunSettings -> command line -> RunSettings ->
// sweep file unchanged, reaches its record column where it has one, is refused out of its
// range naming its key, and the option help and the "known:" lists of a sweep file come from
// its declaration. A setting added to the table is covered here without a word of this file.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "harness/measuring/timing_columns.h"
#include "harness/run/sweep_plan.h"
#include "harness/run/sweep_spec.h"
#include "harness/settings/axis_options.h"
#include "harness/settings/run_command_line.h"
#include "harness/settings/run_setting_options.h"
#include "harness/settings/run_setting_table.h"
#include "harness/util/error.h"
#include "harness/util/text.h"
#include "support/test_support.h"

namespace ldm {
namespace {

using json = nlohmann::json;
using Kind = SettingRule::Kind;

// A value of the setting other than `current`, within its declaration (a real that is not
// round, so that the command line's shortest text is tested).
json other_value(const RunSetting& s, const json& current) {
  switch (s.kind) {
    case Kind::Flag:
      return !current.get<bool>();
    case Kind::Choice:
      for (const auto& c : s.choices)
        if (c != current.get<std::string>()) return c;
      break;
    case Kind::Integer:
      return uint64_t(current.get<double>() != s.min ? s.min : s.min + 1);
    case Kind::Real: {
      const double v = s.positive ? current.get<double>() * 3.7 : s.min + (s.max - s.min) * 0.3137;
      return v != current.get<double>() ? v : s.min;
    }
  }
  ADD_FAILURE() << s.path << ": no other value";
  return current;
}

// The value at a setting's key path in a sweep file's "settings" object, or null.
json value_at(const json& settings, const RunSetting& s) {
  const json* v = &settings;
  for (const std::string& part : {s.group(), s.key()}) {
    if (part.empty()) continue;
    if (!v->is_object() || !v->contains(part)) return nullptr;
    v = &(*v)[part];
  }
  return *v;
}

json settings_with(const RunSetting& s, const json& value) {
  json settings = json::object();
  if (s.group().empty()) settings[s.key()] = value;
  else settings[s.group()][s.key()] = value;
  return settings;
}

std::string write_settings_sweep(const std::string& dir, const json& settings) {
  const std::string path = dir + "/sweep.json";
  std::ofstream(path) << json{{"axes", {{"scenes", "cornell"}}}, {"settings", settings}}.dump(2);
  return path;
}

// `ldmbench run`'s parse of a command line, as far as axes and run-wide settings go (the
// options harness/cli/run_options.cpp adds from the same declarations).
RunSettings parsed_command_line(const std::string& line) {
  std::istringstream words(line);
  std::vector<std::string> args;
  for (std::string w; words >> w;) args.push_back(w);
  EXPECT_GE(args.size(), 2u);
  EXPECT_EQ(args[1], "run");
  args.erase(args.begin(), args.begin() + 2);
  CLI::App app;
  AxisOptions axes;
  add_axis_options(&app, axes);
  RunSettings s;
  RunSettingOptions options;
  add_run_setting_options(&app, s, options);
  std::reverse(args.begin(), args.end());  // CLI11 parses a reversed vector
  app.parse(args);
  apply_axis_options(axes, s);
  apply_run_setting_options(options, s);
  return s;
}

bool same(const json& a, const json& b) {
  if (a.is_number() && b.is_number()) return a.get<double>() == b.get<double>();
  return a == b;
}

TEST(RunSettingTable, EverySettingRoundTripsSweepFileRunSettingsCommandLine) {
  const std::string dir = test::make_temp_dir("ldm-settings");
  ASSERT_FALSE(run_setting_table().empty());
  for (const RunSetting& setting : run_setting_table()) {
    SCOPED_TRACE(setting.path);
    const json value = other_value(setting, run_setting_json(setting, RunSettings()));
    // Sweep file -> RunSettings.
    const SweepPlan plan = plan_sweep(write_settings_sweep(dir, settings_with(setting, value)), RunSettings());
    ASSERT_FALSE(plan.configurations.empty());
    const RunSettings& from_file = plan.configurations.front().settings;
    EXPECT_TRUE(same(run_setting_json(setting, from_file), value))
        << run_setting_json(setting, from_file) << " != " << value;
    // RunSettings -> command line -> RunSettings: this setting and every other one.
    const std::string line = run_command_line(from_file, "ldmbench");
    EXPECT_NE(line.find(" " + setting.flag), std::string::npos) << line;
    const RunSettings from_line = parsed_command_line(line);
    for (const RunSetting& other : run_setting_table())
      EXPECT_TRUE(same(run_setting_json(other, from_line), run_setting_json(other, from_file)))
          << other.path << ": " << run_setting_json(other, from_line) << " != "
          << run_setting_json(other, from_file) << " from: " << line;
    // RunSettings -> sweep file.
    const json file = json::parse(sweep_file_json(from_line));
    EXPECT_TRUE(same(value_at(file["settings"], setting), value)) << file["settings"];
    // The record column, where the setting has one.
    if (setting.column) {
      TimingOutcome timing;
      timing.precision = from_line.precision;
      timing.frames_per_repetition = {1};
      Record r;
      add_timing_columns(r, timing);
      const RecordValue* v = r.get(*setting.column);
      ASSERT_NE(v, nullptr) << setting.column->name;
      ASSERT_TRUE(std::holds_alternative<double>(*v)) << setting.column->name;
      EXPECT_EQ(std::get<double>(*v), value.get<double>()) << setting.column->name;
    }
  }
}

// The keys of `group` ("" the top level) in declared order, as the table gives them.
std::vector<std::string> keys_of(const std::string& group) {
  std::vector<std::string> keys;
  for (const RunSetting& s : run_setting_table()) {
    const std::string key = group.empty() ? (s.group().empty() ? s.key() : s.group()) : s.key();
    if ((group.empty() || s.group() == group) && std::find(keys.begin(), keys.end(), key) == keys.end())
      keys.push_back(key);
  }
  return keys;
}

std::string sweep_error(const json& settings) {
  try {
    parse_sweep_spec(json{{"axes", {{"views", 4}}}, {"settings", settings}}.dump(), "s.json",
                     current_sweep_vocabulary());
  } catch (const UserError& e) {
    return e.what();
  }
  return "";
}

TEST(RunSettingTable, ASweepFileRefusesAValueOutsideTheDeclarationNamingTheKey) {
  for (const RunSetting& setting : run_setting_table()) {
    SCOPED_TRACE(setting.path);
    json bad;
    std::string expected;
    switch (setting.kind) {
      case Kind::Flag:
        bad = 1, expected = "expected true or false";
        break;
      case Kind::Choice:
        bad = "no_such_choice", expected = "expected one of " + joined(setting.choices);
        break;
      case Kind::Integer:
        bad = uint64_t(setting.max) + 1, expected = "expected an integer in [";
        break;
      case Kind::Real:
        bad = setting.positive ? 0.0 : setting.max * 2 + 1;
        expected = setting.positive ? "expected a positive number" : "expected a number in [";
        break;
    }
    const std::string error = sweep_error(settings_with(setting, bad));
    EXPECT_NE(error.find("s.json: settings." + setting.path + ": " + expected), std::string::npos) << error;
    // And the declared value is accepted.
    EXPECT_EQ(sweep_error(settings_with(setting, run_setting_json(setting, RunSettings()))), "");
  }
}

TEST(RunSettingTable, TheKnownKeysAndTheOptionHelpComeFromTheTable) {
  // The top level's keys and each group's.
  std::vector<std::string> known = keys_of("");
  known.push_back("comment");
  EXPECT_NE(sweep_error({{"no_such_key", 1}}).find("settings.no_such_key: unknown key (known: " + joined(known) + ")"),
            std::string::npos)
      << sweep_error({{"no_such_key", 1}});
  for (const RunSetting& setting : run_setting_table()) {
    if (setting.group().empty()) continue;
    const std::string error = sweep_error({{setting.group(), {{"no_such_key", 1}}}});
    EXPECT_NE(error.find("settings." + setting.group() + ".no_such_key: unknown key (known: " +
                         joined(keys_of(setting.group())) + ")"),
              std::string::npos)
        << error;
  }
  // Every setting is an option with its declared help.
  CLI::App app;
  RunSettings s;
  RunSettingOptions options;
  add_run_setting_options(&app, s, options);
  const std::string help = app.help();
  for (const RunSetting& setting : run_setting_table()) {
    EXPECT_NE(help.find(setting.flag), std::string::npos) << setting.flag;
    EXPECT_NE(help.find(setting.help), std::string::npos) << setting.help;
  }
}

}  // namespace
}  // namespace ldm
