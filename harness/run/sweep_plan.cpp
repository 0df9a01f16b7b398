#include "harness/run/sweep_plan.h"

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <set>
#include <sstream>

#include "harness/settings/harness_axes.h"
#include "harness/settings/run_setting_table.h"
#include "harness/run/shard_assignment.h"
#include "harness/passes/pass.h"
#include "harness/scene/generators.h"
#include "harness/scene/scene_loader.h"
#include "harness/util/error.h"
#include "harness/util/json_input.h"
#include "harness/util/hash.h"
#include "ldm_impls/ldm_structure.h"

namespace ldm {
namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;

[[noreturn]] void fail_plan(const std::string& file, const std::string& where, const std::string& what) {
  throw UserError(file + ": " + where + ": " + what);
}

// Calls visit(json path, value) for every value of `axis` in the main axes and include blocks.
void for_each_value(const SweepSpec& spec, const std::string& axis,
                    const std::function<void(const std::string&, const json&)>& visit) {
  for (const auto& [key, values] : spec.axes)
    if (key == axis)
      for (size_t i = 0; i < values.size(); ++i) visit("axes." + key + "[" + std::to_string(i) + "]", values[i]);
  for (size_t b = 0; b < spec.include.size(); ++b) {
    const auto it = spec.include[b].find(axis);
    if (it == spec.include[b].end()) continue;
    for (size_t i = 0; i < it->second.size(); ++i)
      visit("include[" + std::to_string(b) + "]." + axis + "[" + std::to_string(i) + "]", it->second[i]);
  }
}

std::set<std::string> axes_of(const SweepSpec& spec) {
  std::set<std::string> out;
  for (const auto& [key, values] : spec.axes) out.insert(key);
  for (const auto& block : spec.include)
    for (const auto& [key, values] : block) out.insert(key);
  return out;
}

bool is_builtin_scene(const std::string& name) {
  for (const auto& g : scene_generators())
    if (g.name == name) return true;
  return false;
}

// A scene file named relative to the sweep file is found beside it (the sweep folder moves
// with its scenes); otherwise the name is a built-in scene or a path from the working folder.
std::string resolve_scene(const std::string& spec, const fs::path& sweep_dir) {
  if (is_builtin_scene(spec) || fs::path(spec).is_absolute()) return spec;
  std::error_code error;
  const fs::path beside = sweep_dir / spec;
  if (!sweep_dir.empty() && fs::exists(beside, error)) return beside.lexically_normal().string();
  return spec;
}

// Every declared run-wide setting the file gives (checked by parse_sweep_spec), by its
// declaration (harness/settings/run_setting_table.h).
void apply_settings(const json& settings, RunSettings& s) {
  for (const RunSetting& setting : run_setting_table()) {
    const json* value = &settings;
    for (const std::string& part : {setting.group(), setting.key()}) {
      if (part.empty()) continue;
      value = value->is_object() && value->contains(part) ? &(*value)[part] : nullptr;
      if (!value) break;
    }
    if (value) set_run_setting_json(setting, s, *value);
  }
}

// The RunSettings of one combination: one value per axis, through each axis's binding; the
// axes it does not name keep `ldmbench run`'s defaults.
RunSettings combination_settings(const SweepAssignment& a, const RunSettings& base,
                                 const std::map<std::string, std::string>& scene_paths) {
  RunSettings s = base;
  s.structure_params.clear();
  for (const HarnessAxis& axis : harness_axes()) {
    const auto it = a.find(axis.spec.key);
    if (it == a.end()) continue;
    std::string text = axis_text_of_json(it->second, axis.spec.key);
    if (axis.spec.key == "scenes") text = scene_paths.at(text);
    set_axis_list(s, axis, {text});
  }
  // The budget belongs to the budget policy only (run refuses it with another policy).
  if (a.count("sizing_budget_mib") && s.sizing.front() != SizingPolicy::Budget) s.sizing_budget_mib = 0;
  // OWNER:KEY applies when its structure or pass is the combination's (else it is an axis
  // this configuration does not use).
  for (const auto& [key, value] : a) {
    const auto colon = key.find(':');
    if (colon == std::string::npos) continue;
    const std::string owner = key.substr(0, colon);
    if (owner == s.structures.front() || owner == s.passes.front())
      s.structure_params[owner][key.substr(colon + 1)] = value.get<std::string>();
  }
  return s;
}

}  // namespace

Shard parse_shard(const std::string& text) {
  Shard shard;
  const auto slash = text.find('/');
  const auto digits = [](const std::string& t) {
    return !t.empty() && t.size() <= 9 && t.find_first_not_of("0123456789") == std::string::npos;
  };
  if (slash == std::string::npos || !digits(text.substr(0, slash)) || !digits(text.substr(slash + 1)))
    throw UserError("--shard '" + text + "': expected INDEX/COUNT with 0 <= INDEX < COUNT (e.g. 0/8)");
  shard.index = std::stoul(text.substr(0, slash));
  shard.count = std::stoul(text.substr(slash + 1));
  if (shard.count == 0 || shard.index >= shard.count)
    throw UserError("--shard '" + text + "': expected INDEX/COUNT with 0 <= INDEX < COUNT (e.g. 0/8)");
  return shard;
}

std::vector<size_t> shard_members(const SweepPlan& plan, const Shard& shard) {
  std::vector<std::map<std::string, std::string>> values;
  for (const auto& planned : plan.configurations) values.push_back(planned.config.values);
  const std::vector<size_t> shard_of = assign_shards(values, shard.count);
  std::vector<size_t> members;
  for (size_t k = 0; k < shard_of.size(); ++k)
    if (shard_of[k] == shard.index) members.push_back(k);
  return members;
}

SweepVocabulary current_sweep_vocabulary() {
  SweepVocabulary v;
  for (const HarnessAxis& axis : harness_axes()) v.axes.push_back(axis.spec);
  for (const auto& name : structure_names()) v.parameters[name] = structure_parameters(name);
  for (const auto& name : pass_names()) v.parameters[name] = pass_parameters(name);
  v.settings = run_setting_rules();
  return v;
}

SweepPlan plan_sweep(const std::string& path, const RunSettings& base) {
  const std::string file = fs::path(path).filename().string();
  // A folder, a missing file or one beyond the input limit is refused before reading it.
  const std::string text = read_input_file(path, "sweep file");

  SweepPlan plan;
  plan.path = path;
  plan.spec = parse_sweep_spec(text, file, current_sweep_vocabulary());
  const SweepSpec& spec = plan.spec;
  plan.sweep_hash = hex64([&] {
    Fnv1a h;
    h.add_string(spec.canonical);
    return h.value();
  }());

  // Scenes: loaded once each, errors at their JSON path.
  std::map<std::string, std::string> scene_paths;
  const fs::path sweep_dir = fs::path(path).parent_path();
  for_each_value(spec, "scenes", [&](const std::string& where, const json& v) {
    const std::string name = v.get<std::string>();
    const std::string resolved = resolve_scene(name, sweep_dir);
    scene_paths[name] = resolved;
    if (plan.scenes.count(resolved)) return;
    try {
      plan.scenes.emplace(resolved, load_scene(resolved));
    } catch (const UserError& e) {
      fail_plan(file, where, e.what());
    }
  });
  const std::set<std::string> axes = axes_of(spec);
  if (axes.count("sizing_budget_mib") && !axes.count("sizing"))
    fail_plan(file, "axes.sizing_budget_mib", "is used only by the budget sizing policy; add \"sizing\": \"budget\"");

  RunSettings shared = base;
  apply_settings(spec.settings, shared);
  const std::vector<SweepAssignment> combinations = sweep_combinations(plan.spec);
  plan.combinations = combinations.size();

  // The axes the sweep gives more than one value: what `ldmbench run` holds fixed (image
  // size, frames) is named in the ids only then.
  std::set<std::string> varied;
  {
    std::map<std::string, std::set<std::vector<std::string>>> seen;
    for (const auto& a : combinations) {
      const RunSettings s = combination_settings(a, shared, scene_paths);
      for (const HarnessAxis& axis : harness_axes()) seen[axis.spec.key].insert(axis_list(s, axis));
    }
    for (const auto& [key, values] : seen)
      if (values.size() > 1) varied.insert(key);
  }

  std::set<std::string> ids;
  for (const auto& a : combinations) {
    const RunSettings s = combination_settings(a, shared, scene_paths);
    try {
      if (s.sizing.front() == SizingPolicy::Budget && s.sizing_budget_mib <= 0)
        throw UserError("the budget sizing policy needs sizing_budget_mib (an axis of MiB values)");
      validate_axes(s);
    } catch (const UserError& e) {
      fail_plan(file, "combination " + json(a).dump(), e.what());
    }
    for (Configuration config : expand_configurations(s)) {
      config.id_ = configuration_id(config.values, varied);
      if (!ids.insert(config.id()).second) continue;  // an axis this configuration does not use
      plan.configurations.push_back({config, s});
    }
  }
  if (plan.configurations.empty()) fail_plan(file, "(top level)", "the sweep has no configuration (everything excluded)");
  // A combination that names no scene runs the default one, also when only an include
  // block names scenes (the main axes then have none): load every scene a configuration uses.
  for (const auto& planned : plan.configurations)
    if (!plan.scenes.count(planned.config.scene))
      plan.scenes.emplace(planned.config.scene, load_scene(planned.config.scene));
  return plan;
}

}  // namespace ldm
