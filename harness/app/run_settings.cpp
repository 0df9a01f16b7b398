#include "harness/app/run_settings.h"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <filesystem>

#include "harness/passes/pass.h"
#include "harness/scene/scene_loader.h"
#include "harness/util/error.h"

namespace ldm {

const char* repetition_isolation_name(RepetitionIsolation isolation) {
  return isolation == RepetitionIsolation::Process ? "process" : "context";
}

RepetitionIsolation parse_repetition_isolation(const std::string& name) {
  if (name == "process") return RepetitionIsolation::Process;
  if (name == "context") return RepetitionIsolation::Context;
  throw UserError("--isolation: '" + name + "' is not context or process");
}

std::string visibility_name(Visibility v) {
  switch (v) {
    case Visibility::Attenuated: return "attenuated";
    case Visibility::Unattenuated: return "unattenuated";
    default: return "scene";
  }
}

std::string Configuration::id() const {
  // The scene's own name (a scene file's "name"), not its file name (issue 22).
  std::string scene_name = scene_id_name(scene);
  // A pass that reads no LDM (structure none) has no N, R_LDM, trace or sizing: its id
  // names only what applies to it, scene-none-<pass>[-d..][-att][-k=v...].
  const bool ldm = structure != kNoStructure;
  std::string id = scene_name + "-" + structure + "-" + pass;
  if (ldm) id += "-n" + std::to_string(views) + "-r" + std::to_string(resolution);
  if (d_max) {
    char buffer[32];
    std::snprintf(buffer, sizeof buffer, "-d%g", *d_max);
    id += buffer;
  }
  if (visibility == Visibility::Attenuated) id += "-att";
  if (visibility == Visibility::Unattenuated) id += "-unatt";
  if (ldm) id += "-" + ao_trace_name(trace);  // LDM AO only
  if (estimator != AoEstimatorChoice::Eq13) id += "-" + ao_estimator_name(estimator);
  for (const auto& [key, value] : params) id += "-" + key + "=" + value;
  // A pass's own --param values (not the AO axes above, which the id already names).
  static const char* const kAoAxes[] = {"d_max", "visibility", "normal_offset_pixels", "trace",
                                        "ao_estimator"};
  if (ldm)
    for (const auto& [key, value] : pass_params)
      if (std::find(std::begin(kAoAxes), std::end(kAoAxes), key) == std::end(kAoAxes))
        id += "-" + key + "=" + value;
  if (ldm) switch (sizing.policy) {
    case SizingPolicy::Oracle: id += "-oracle"; break;
    case SizingPolicy::Census: id += "-census"; break;
    case SizingPolicy::PreviousFrame:
      id += "-prevframe";
      if (sizing.initial_per_pixel != 1) id += "-guess" + std::to_string(sizing.initial_per_pixel);
      break;
    case SizingPolicy::Budget: {
      char buffer[32];
      std::snprintf(buffer, sizeof buffer, "-budget%g", double(sizing.budget_bytes) / double(1u << 20));
      id += buffer;
      break;
    }
  }
  id += id_suffix;
  for (char& c : id)
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_' || c == '.' || c == '='))
      c = '_';
  return id;
}

namespace {

// Round-trips a float through text (the pass reads it back with strtod).
std::string float_text(float value) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.9g", double(value));
  return buffer;
}

// A parameter whose value is a comma list is an axis, like -N 16,32: every combination of
// the lists of one structure's (or pass's) parameters is one configuration. `owner` names
// the structure or pass for the message on an empty item (-param ppfla:k=4,,8).
std::vector<std::map<std::string, std::string>> parameter_combinations(
    const std::string& owner, const std::map<std::string, std::string>& params) {
  std::vector<std::map<std::string, std::string>> combinations = {{}};
  for (const auto& [key, list] : params) {
    std::vector<std::string> values;
    for (size_t start = 0;;) {
      const size_t comma = list.find(',', start);
      values.push_back(list.substr(start, comma == std::string::npos ? comma : comma - start));
      if (values.back().empty())
        throw UserError("--param " + owner + ":" + key + "=" + list +
                        ": empty item in the comma list");
      if (comma == std::string::npos) break;
      start = comma + 1;
    }
    std::vector<std::map<std::string, std::string>> grown;
    for (const auto& combination : combinations)
      for (const auto& value : values) {
        grown.push_back(combination);
        grown.back()[key] = value;
      }
    combinations = std::move(grown);
  }
  return combinations;
}

const std::map<std::string, std::string>& params_of(const RunSettings& s, const std::string& owner) {
  static const std::map<std::string, std::string> none;
  const auto found = s.structure_params.find(owner);
  return found == s.structure_params.end() ? none : found->second;
}

}  // namespace

// Two scenes known by one name would share configuration ids (and a journal would take one
// for the other's finished configuration).
void check_scene_names_are_distinct(const std::vector<std::string>& scenes) {
  std::map<std::string, std::string> spec_of;
  for (const auto& spec : scenes) {
    const auto [it, added] = spec_of.emplace(scene_id_name(spec), spec);
    if (!added && it->second != spec)
      throw UserError("--scene: '" + it->second + "' and '" + spec + "' are both named '" +
                      it->first + "', so their configurations would have the same ids; give one "
                      "of them another \"name\"");
  }
}

std::vector<Configuration> expand_configurations(const RunSettings& s) {
  check_scene_names_are_distinct(s.scenes);
  std::vector<Configuration> out;
  const std::vector<std::optional<float>> d_values =
      s.d_max.empty() ? std::vector<std::optional<float>>{std::nullopt}
                      : std::vector<std::optional<float>>(s.d_max.begin(), s.d_max.end());
  for (const auto& scene : s.scenes)
    for (const auto& pass : s.passes) {
      // A peer that reads no LDM (HBAO) is one configuration per scene and AO setting: the
      // structure, N, R_LDM, trace and estimator axes do not apply to it.
      if (!make_pass(pass, StructureParams())->requirements().needs_structure) {
        for (const auto& d : d_values)
          for (Visibility v : s.visibility)
            for (const auto& params : parameter_combinations(pass, params_of(s, pass))) {
            Configuration c;
            c.scene = scene;
            c.structure = kNoStructure;
            c.pass = pass;
            c.views = 0;
            c.resolution = 0;
            c.d_max = d;
            c.visibility = v;
            c.params = c.pass_params = params;  // --param hbao:steps=8,16
            if (d) c.pass_params["d_max"] = float_text(*d);
            if (v != Visibility::Scene) c.pass_params["visibility"] = visibility_name(v);
            out.push_back(c);
          }
        continue;
      }
      for (const auto& structure : s.structures)
        for (const auto& params : parameter_combinations(structure, params_of(s, structure)))
        for (uint32_t n : s.views)
          for (uint32_t r : s.resolutions)
            for (const auto& d : d_values)
              for (Visibility v : s.visibility)
                for (AoTrace trace : s.traces)
                  for (AoEstimatorChoice estimator : s.estimators)
                    for (SizingPolicy sizing : s.sizing)
                    for (const auto& own : parameter_combinations(pass, params_of(s, pass))) {
                    Configuration c;
                    c.pass_params = own;  // the pass's own --param pass:KEY=VALUE
                    c.scene = scene;
                    c.structure = structure;
                    c.pass = pass;
                    c.views = n;
                    c.resolution = r;
                    c.d_max = d;
                    c.visibility = v;
                    c.trace = trace;
                    c.estimator = estimator;
                    c.params = params;
                    if (d) c.pass_params["d_max"] = float_text(*d);
                    if (v != Visibility::Scene) c.pass_params["visibility"] = visibility_name(v);
                    if (s.normal_offset_pixels)
                      c.pass_params["normal_offset_pixels"] = float_text(*s.normal_offset_pixels);
                    c.pass_params["trace"] = ao_trace_name(trace);
                    c.pass_params["ao_estimator"] = ao_estimator_name(estimator);
                    c.sizing.policy = sizing;
                    c.sizing.budget_bytes = uint64_t(s.sizing_budget_mib * double(1u << 20));
                    c.sizing.initial_per_pixel = s.sizing_initial_per_pixel;
                    out.push_back(c);
                  }
    }
  return out;
}

}  // namespace ldm
