#include "harness/run/sweep_spec.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <set>

#include "harness/axes/axis.h"
#include "harness/util/error.h"
#include "harness/util/json_input.h"
#include "harness/util/text.h"

namespace ldm {
namespace {

using json = nlohmann::json;

std::string number_text(double x) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.9g", x);
  return buffer;
}

[[noreturn]] void fail_spec(const std::string& name, const std::string& path, const std::string& what) {
  throw UserError(name + ": " + path + ": " + what);
}

std::string type_name(const json& v) {
  if (v.is_number_integer()) return "an integer";
  if (v.is_number()) return "a number";
  return std::string("a ") + v.type_name();
}

// canonical_axis_value's "<where>: " prefix is the JSON path here, so the message is the part
// after it.
std::string checked(const AxisSpec& spec, const std::string& text, const std::string& name,
                    const std::string& path) {
  try {
    return canonical_axis_value(spec, text, path);
  } catch (const UserError& e) {
    fail_spec(name, path, std::string(e.what()).substr(path.size() + 2));
  }
}

// Checks one axis value (its JSON type by the axis's kind, then its declaration) and returns
// it in canonical form: numbers as JSON numbers, names and sizes as strings; a parameter's
// value as the text --param would carry.
json canonical_value(const AxisSpec& spec, bool parameter, const json& v, const std::string& name,
                     const std::string& path) {
  if (parameter) {
    // A comma would make it a list on the command line: in a file, lists are arrays.
    if (v.is_string() && v.get<std::string>().find(',') != std::string::npos)
      fail_spec(name, path, "a comma in a parameter value; give several values as an array");
    std::string text;
    try {
      text = axis_text_of_json(v, path);
    } catch (const UserError& e) {
      fail_spec(name, path, std::string(e.what()).substr(path.size() + 2));
    }
    return json(checked(spec, text, name, path));
  }
  const std::string what = spec.display_name();
  switch (spec.kind) {
    case AxisKind::UInt:
      if (!v.is_number_integer()) fail_spec(name, path, "expected an integer (" + what + "), got " + type_name(v));
      if (!v.is_number_unsigned() && v.get<int64_t>() < 0)
        fail_spec(name, path, what + " " + v.dump() + " is out of range [" + number_text(spec.min) + ", " +
                             number_text(spec.max) + "]");
      return axis_json_of_text(spec, checked(spec, std::to_string(v.get<uint64_t>()), name, path));
    case AxisKind::Real:
      if (!v.is_number()) fail_spec(name, path, "expected a number (" + what + "), got " + type_name(v));
      return axis_json_of_text(spec, checked(spec, axis_text_of_json(v, path), name, path));
    case AxisKind::ImageSize:
      if (v.is_number_unsigned())
        return json(checked(spec, std::to_string(std::min<uint64_t>(v.get<uint64_t>(), 1u << 30)), name, path));
      if (!v.is_string())
        fail_spec(name, path, "expected an image size \"WIDTHxHEIGHT\" or one integer, got " + type_name(v));
      return json(checked(spec, v.get<std::string>(), name, path));
    case AxisKind::Bool:
      if (!v.is_boolean()) fail_spec(name, path, "expected true or false, got " + type_name(v));
      return json(v.get<bool>());
    case AxisKind::Choice:
      if (!v.is_string()) fail_spec(name, path, "expected a " + what + " name, got " + type_name(v));
      if (spec.key == "structures") {
        const auto names = axis_choices(spec);
        if (std::find(names.begin(), names.end(), v.get<std::string>()) == names.end())
          fail_spec(name, path, "unknown structure \"" + v.get<std::string>() + "\" (known: " + joined(names) + ", or all)");
      } else {
        const auto names = axis_choices(spec);
        if (std::find(names.begin(), names.end(), v.get<std::string>()) == names.end())
          fail_spec(name, path, "unknown " + what + " \"" + v.get<std::string>() + "\" (known: " + joined(names) + ")");
      }
      return v;
    case AxisKind::Text:
      if (!v.is_string() || v.get<std::string>().empty())
        fail_spec(name, path, "expected a non-empty string, got " + type_name(v));
      return v;
  }
  fail_spec(name, path, "unhandled axis kind");
}

std::vector<std::string> axis_keys(const SweepVocabulary& v) {
  std::vector<std::string> keys;
  for (const auto& a : v.axes) keys.push_back(a.key);
  return keys;
}

// The declaration of an axis key: a harness axis, or OWNER:KEY (a parameter of a structure
// or pass); `parameter` tells which.
const AxisSpec& axis_rule(const std::string& key, const SweepVocabulary& v, const std::string& name,
                          const std::string& path, bool& parameter) {
  parameter = false;
  if (const AxisSpec* known = find_axis(v.axes, key)) return *known;
  const auto colon = key.find(':');
  if (colon == std::string::npos)
    fail_spec(name, path, "unknown axis \"" + key + "\" (axes: " + joined(axis_keys(v)) +
                         ", or OWNER:KEY for a --param)");
  if (colon == 0 || colon + 1 >= key.size() || key.find(':', colon + 1) != std::string::npos)
    fail_spec(name, path, "expected OWNER:KEY (a --param of a structure or pass, e.g. \"ppfla:k\")");
  const std::string owner = key.substr(0, colon), param = key.substr(colon + 1);
  const auto declared = v.parameters.find(owner);
  if (declared == v.parameters.end()) {
    std::vector<std::string> owners;
    for (const auto& [o, specs] : v.parameters) owners.push_back(o);
    fail_spec(name, path, "unknown structure or pass \"" + owner + "\" (known: " + joined(owners) + ")");
  }
  const AxisSpec* spec = find_axis(declared->second, param);
  std::vector<std::string> keys;
  for (const auto& s : declared->second)
    if (s.pass_parameter.empty()) keys.push_back(s.key);
  if (!spec)
    fail_spec(name, path, owner + " has no parameter \"" + param + "\" (its parameters: " +
                         (keys.empty() ? std::string("none") : joined(keys)) + ")");
  if (!spec->pass_parameter.empty())
    fail_spec(name, path, "set it with the axis of the same setting (\"" + [&] {
      for (const auto& a : v.axes)
        if (a.pass_parameter == param) return a.key;
      return param;
    }() + "\"), not as a parameter of " + owner);
  parameter = true;
  return *spec;
}

// The values of one axis (an array, or a single value), canonical, duplicates refused;
// "all" structures expanded.
std::vector<json> axis_values(const std::string& key, const json& value, const SweepVocabulary& vocabulary,
                              const std::string& name, const std::string& path) {
  bool parameter = false;
  const AxisSpec& rule = axis_rule(key, vocabulary, name, path, parameter);
  const json items = value.is_array() ? value : json::array({value});
  if (items.empty()) fail_spec(name, path, "an axis needs at least one value");
  std::vector<json> out;
  for (size_t i = 0; i < items.size(); ++i) {
    const std::string item_path = value.is_array() ? path + "[" + std::to_string(i) + "]" : path;
    if (!parameter && rule.key == "structures" && items[i] == "all") {
      for (const auto& s : axis_choices(rule))
        if (std::find(out.begin(), out.end(), json(s)) == out.end()) out.push_back(json(s));
      continue;
    }
    json v = canonical_value(rule, parameter, items[i], name, item_path);
    if (std::find(out.begin(), out.end(), v) != out.end())
      fail_spec(name, item_path, v.dump() + " appears twice");
    out.push_back(std::move(v));
  }
  return out;
}

void require_object(const json& v, const std::string& name, const std::string& path) {
  if (!v.is_object()) fail_spec(name, path, "expected an object, got " + type_name(v));
}

// axis -> values, the form of the axes, of include blocks and of exclude filters.
std::map<std::string, std::vector<json>> axis_block(const json& object,
                                                    const SweepVocabulary& vocabulary,
                                                    const std::string& name,
                                                    const std::string& path) {
  require_object(object, name, path);
  std::map<std::string, std::vector<json>> out;
  for (const auto& [key, value] : object.items()) {
    if (key == "comment") continue;  // a note for readers
    out[key] = axis_values(key, value, vocabulary, name, path + "." + key);
  }
  return out;
}

// The keys of the settings object at `group` ("" the top level, "timing"...), in declared order:
// a setting's own key, or the group it belongs to.
std::vector<std::string> setting_keys(const std::vector<SettingRule>& rules, const std::string& group) {
  std::vector<std::string> keys;
  for (const auto& r : rules) {
    if (!group.empty() && r.path.rfind(group + ".", 0) != 0) continue;
    std::string key = group.empty() ? r.path : r.path.substr(group.size() + 1);
    key = key.substr(0, key.find('.'));
    if (std::find(keys.begin(), keys.end(), key) == keys.end()) keys.push_back(key);
  }
  return keys;
}

const SettingRule* find_setting_rule(const std::vector<SettingRule>& rules, const std::string& path) {
  for (const auto& r : rules)
    if (r.path == path) return &r;
  return nullptr;
}

// One value by its declared rule.
void check_setting_value(const SettingRule& rule, const json& value, const std::string& name,
                         const std::string& path) {
  switch (rule.kind) {
    case SettingRule::Kind::Flag:
      if (!value.is_boolean()) fail_spec(name, path, "expected true or false, got " + type_name(value));
      return;
    case SettingRule::Kind::Choice:
      if (!value.is_string() ||
          std::find(rule.choices.begin(), rule.choices.end(), value.get<std::string>()) == rule.choices.end())
        fail_spec(name, path, "expected one of " + joined(rule.choices) + ", got " + value.dump());
      return;
    case SettingRule::Kind::Integer:
      if (!value.is_number_unsigned() || double(value.get<uint64_t>()) > rule.max ||
          double(value.get<uint64_t>()) < rule.min)
        fail_spec(name, path, "expected an integer in [" + number_text(rule.min) + ", " + number_text(rule.max) +
                             "], got " + value.dump());
      return;
    case SettingRule::Kind::Real: {
      if (rule.positive) {
        if (!value.is_number() || !(value.get<double>() > 0) || !std::isfinite(value.get<double>()))
          fail_spec(name, path, "expected a positive number, got " + value.dump());
        return;
      }
      const double v = value.is_number() ? value.get<double>() : -1;
      if (!value.is_number() || !(v >= rule.min) || v > rule.max)
        fail_spec(name, path, "expected a number in [" + number_text(rule.min) + ", " + number_text(rule.max) +
                             "], got " + value.dump());
      return;
    }
  }
}

// The object at `group` of the settings ("" the top level): every key a declared setting or a
// group of them, each value by its rule.
void check_setting_group(const json& object, const std::vector<SettingRule>& rules, const std::string& group,
                         const std::string& name, const std::string& path) {
  require_object(object, name, path);
  for (const auto& [key, value] : object.items()) {
    const std::string item_path = path + "." + key;
    if (group.empty() && key == "comment") continue;
    const std::string setting = group.empty() ? key : group + "." + key;
    if (const SettingRule* rule = find_setting_rule(rules, setting)) {
      check_setting_value(*rule, value, name, item_path);
      continue;
    }
    const std::vector<std::string> inner = setting_keys(rules, setting);
    if (!inner.empty()) {
      check_setting_group(value, rules, setting, name, item_path);
      continue;
    }
    std::vector<std::string> known = setting_keys(rules, group);
    if (group.empty()) known.push_back("comment");
    fail_spec(name, item_path, "unknown key (known: " + joined(known) + ")");
  }
}

void check_settings(const json& settings, const std::vector<SettingRule>& rules, const std::string& name) {
  check_setting_group(settings, rules, "", name, "settings");
  // Between two settings: the reference's fixed spp within its cap.
  if (settings.contains("reference")) {
    const json& value = settings["reference"];
    if (value.contains("spp") && value.contains("max_spp") &&
        value["spp"].get<uint64_t>() > value["max_spp"].get<uint64_t>())
      fail_spec(name, "settings.reference.spp", "exceeds settings.reference.max_spp");
  }
}

size_t axis_order(const std::vector<std::string>& names, const std::string& key) {
  const auto it = std::find(names.begin(), names.end(), key);
  return it == names.end() ? names.size() : size_t(it - names.begin());
}

// What identifies a sweep: its content without notes (description, comment), dumped with
// sorted keys (nlohmann::json's order), so formatting, key order and notes do not count.
std::string identity_text(json root) {
  root.erase("description");
  root.erase("comment");
  for (const char* key : {"axes", "settings"})
    if (root.contains(key) && root[key].is_object()) root[key].erase("comment");
  for (const char* list : {"include", "exclude"})
    if (root.contains(list) && root[list].is_array())
      for (auto& block : root[list])
        if (block.is_object()) block.erase("comment");
  return root.dump();
}

}  // namespace

SweepSpec parse_sweep_spec(const std::string& text, const std::string& name,
                           const SweepVocabulary& vocabulary) {
  SweepSpec spec;
  spec.name = name;
  // Syntax errors and numbers beyond double (1e400, a fuzzer finding) with their line, keys
  // given twice and nesting beyond kMaxJsonDepth refused (util/json_input.h).
  const json root = parse_json_strictly(text, name);
  require_object(root, name, "(top level)");
  const std::vector<std::string> order = axis_keys(vocabulary);
  for (const auto& [key, value] : root.items()) {
    if (key == "axes" || key == "include" || key == "exclude" || key == "settings") continue;
    if (key == "description" || key == "comment") {
      const bool text_or_lines = value.is_string() ||
          (value.is_array() && std::all_of(value.begin(), value.end(), [](const json& l) { return l.is_string(); }));
      if (!text_or_lines) fail_spec(name, key, "expected a string or an array of strings");
      if (key == "description" && value.is_string()) spec.description = value.get<std::string>();
      continue;
    }
    fail_spec(name, key, "unknown key (known: description, comment, axes, include, exclude, settings)");
  }
  if (!root.contains("axes")) fail_spec(name, "axes", "missing (the object of axes to sweep)");
  const auto axes = axis_block(root["axes"], vocabulary, name, "axes");
  for (const auto& [key, values] : axes) spec.axes.emplace_back(key, values);
  spec.axis_order = order;
  std::stable_sort(spec.axes.begin(), spec.axes.end(), [&order](const auto& a, const auto& b) {
    const size_t oa = axis_order(order, a.first), ob = axis_order(order, b.first);
    return oa != ob ? oa < ob : a.first < b.first;
  });
  for (const char* list : {"include", "exclude"}) {
    if (!root.contains(list)) continue;
    const json& entries = root[list];
    if (!entries.is_array()) fail_spec(name, list, "expected an array of objects, got " + type_name(entries));
    for (size_t i = 0; i < entries.size(); ++i) {
      const std::string path = std::string(list) + "[" + std::to_string(i) + "]";
      auto block = axis_block(entries[i], vocabulary, name, path);
      if (block.empty()) fail_spec(name, path, "names no axis");
      for (const auto& [key, values] : block) {
        (void)values;
        // A filter on an axis the sweep does not vary would compare with a default it
        // cannot see; an include block may add any axis (its first values are new).
        if (std::string(list) == "exclude" && !axes.count(key))
          fail_spec(name, path + "." + key, "not an axis of this sweep (axes: " + [&] {
            std::vector<std::string> keys;
            for (const auto& a : spec.axes) keys.push_back(a.first);
            return joined(keys);
          }() + ")");
      }
      (std::string(list) == "include" ? spec.include : spec.exclude).push_back(std::move(block));
    }
  }
  if (root.contains("settings")) {
    check_settings(root["settings"], vocabulary.settings, name);
    spec.settings = root["settings"];
  }
  spec.canonical = identity_text(root);
  return spec;
}

std::vector<SweepAssignment> sweep_combinations(SweepSpec& spec) {
  std::vector<std::map<std::string, std::vector<json>>> blocks;
  std::map<std::string, std::vector<json>> main;
  for (const auto& [key, values] : spec.axes) main[key] = values;
  blocks.push_back(main);
  for (const auto& include : spec.include) {
    auto block = main;
    for (const auto& [key, values] : include) block[key] = values;
    blocks.push_back(std::move(block));
  }
  std::vector<std::string> order;  // canonical order over every axis any block names
  for (const auto& block : blocks)
    for (const auto& [key, values] : block) {
      (void)values;
      if (std::find(order.begin(), order.end(), key) == order.end()) order.push_back(key);
    }
  std::stable_sort(order.begin(), order.end(), [&spec](const std::string& a, const std::string& b) {
    const size_t oa = axis_order(spec.axis_order, a), ob = axis_order(spec.axis_order, b);
    return oa != ob ? oa < ob : a < b;
  });

  size_t total = 0;
  for (const auto& block : blocks) {
    size_t size = 1;
    for (const auto& [key, values] : block) {
      (void)key;
      if (size > kMaxSweepCombinations / values.size()) size = kMaxSweepCombinations + 1;
      else size *= values.size();
    }
    total += size;
    if (total > kMaxSweepCombinations)
      throw UserError(spec.name + ": the sweep has more than " + std::to_string(kMaxSweepCombinations) +
                      " combinations");
  }

  std::vector<size_t> matched(spec.exclude.size(), 0);
  auto excluded = [&](const SweepAssignment& a) {
    bool any = false;
    for (size_t f = 0; f < spec.exclude.size(); ++f) {
      bool all = true;
      for (const auto& [key, values] : spec.exclude[f]) {
        const auto it = a.find(key);
        if (it == a.end() || std::find(values.begin(), values.end(), it->second) == values.end()) {
          all = false;
          break;
        }
      }
      if (all) {
        ++matched[f];
        any = true;
      }
    }
    return any;
  };

  std::vector<SweepAssignment> out;
  std::set<std::string> seen;
  for (const auto& block : blocks) {
    std::vector<std::string> keys;
    for (const auto& key : order)
      if (block.count(key)) keys.push_back(key);
    std::vector<size_t> index(keys.size(), 0);
    for (bool more = true; more;) {
      SweepAssignment a;
      for (size_t k = 0; k < keys.size(); ++k) a[keys[k]] = block.at(keys[k])[index[k]];
      if (!excluded(a) && seen.insert(json(a).dump()).second) out.push_back(std::move(a));
      // Odometer: the last axis fastest.
      more = false;
      for (size_t k = keys.size(); k-- > 0;) {
        if (++index[k] < block.at(keys[k]).size()) {
          more = true;
          break;
        }
        index[k] = 0;
      }
    }
  }
  for (size_t f = 0; f < spec.exclude.size(); ++f)
    if (matched[f] == 0)
      spec.warnings.push_back(spec.name + ": exclude[" + std::to_string(f) +
                              "] matches no combination (it removes nothing)");
  return out;
}

}  // namespace ldm
