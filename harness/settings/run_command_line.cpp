#include "harness/settings/run_command_line.h"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <functional>

#include <nlohmann/json.hpp>

#include "harness/settings/harness_axes.h"
#include "harness/settings/run_setting_table.h"

namespace ldm {
namespace {

template <typename T, typename Name>
std::string joined(const std::vector<T>& values, Name name) {
  std::string out;
  for (const auto& v : values) out += (out.empty() ? "" : ",") + name(v);
  return out;
}

}  // namespace

std::string shell_quoted(const std::string& word) {
  bool safe = !word.empty();
  for (char c : word)
    safe = safe && (std::isalnum(static_cast<unsigned char>(c)) ||
                    std::string("-_./:=,+@%").find(c) != std::string::npos);
  if (safe) return word;
  std::string out = "'";
  for (char c : word) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

namespace {

// Parameters of a structure or pass not measured are left out (run refuses them).
bool measured(const RunSettings& s, const std::string& owner) {
  return std::find(s.structures.begin(), s.structures.end(), owner) != s.structures.end() ||
         std::find(s.passes.begin(), s.passes.end(), owner) != s.passes.end();
}

std::vector<std::string> split_commas(const std::string& list) {
  std::vector<std::string> out;
  for (size_t start = 0;;) {
    const size_t comma = list.find(',', start);
    out.push_back(list.substr(start, comma == std::string::npos ? comma : comma - start));
    if (comma == std::string::npos) return out;
    start = comma + 1;
  }
}

}  // namespace

std::string run_command_line(const RunSettings& s, const std::string& program,
                             const std::string& out_dir) {
  std::string line = shell_quoted(program) + " run";
  auto add = [&line](const std::string& option, const std::string& value) {
    line += " " + option + " " + shell_quoted(value);
  };
  // Every harness axis that has values, from its declaration and binding.
  for (const HarnessAxis& axis : harness_axes()) {
    if (axis.spec.flags.empty()) continue;
    const std::vector<std::string> values = axis_list(s, axis);
    if (values.empty()) continue;
    std::string list;
    for (const auto& v : values) list += (list.empty() ? "" : ",") + v;
    add(long_flag(axis.spec.flags), list);
  }
  for (const auto& [owner, params] : s.structure_params)
    if (measured(s, owner))
      for (const auto& [key, value] : params) add("--param", owner + ":" + key + "=" + value);
  // Every run-wide setting from its declaration (harness/settings/run_setting_table.h): a flag
  // only when off (--no-images), the others always, with their value.
  for (const RunSetting& setting : run_setting_table()) {
    if (!run_setting_written(setting, s)) continue;
    if (setting.kind == SettingRule::Kind::Flag) {
      if (!run_setting_json(setting, s).get<bool>()) line += " " + setting.flag;
    } else {
      add(setting.flag, run_setting_text(setting, s));
    }
  }
  if (s.reference.enabled && !s.reference.cache_dir.empty()) add("--cache-dir", s.reference.cache_dir);
  if (!out_dir.empty()) add("--out", out_dir);
  return line;
}

std::string sweep_file_json(const RunSettings& s, const std::string& description) {
  using nlohmann::json;
  json axes = json::object();
  for (const HarnessAxis& axis : harness_axes()) {
    const std::vector<std::string> values = axis_list(s, axis);
    if (values.empty()) continue;
    json list = json::array();
    for (const auto& v : values) list.push_back(axis_json_of_text(axis.spec, v));
    axes[axis.spec.key] = list.size() == 1 ? list[0] : list;
  }
  // Parameters of a structure or pass not measured are left out, as on the command line; a
  // comma list is an array.
  for (const auto& [owner, params] : s.structure_params)
    if (measured(s, owner))
      for (const auto& [key, value] : params) {
        const std::vector<std::string> values = split_commas(value);
        axes[owner + ":" + key] = values.size() == 1 ? json(values[0]) : json(values);
      }

  json file = json::object();
  if (!description.empty()) file["description"] = description;
  file["axes"] = axes;
  // Every run-wide setting from its declaration, at its key path under "settings".
  json settings = json::object();
  for (const RunSetting& setting : run_setting_table()) {
    if (!run_setting_written(setting, s)) continue;
    json& place = setting.group().empty() ? settings : settings[setting.group()];
    place[setting.key()] = run_setting_json(setting, s);
  }
  file["settings"] = settings;
  return file.dump(2) + "\n";
}

}  // namespace ldm
