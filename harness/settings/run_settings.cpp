#include "harness/settings/run_settings.h"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <filesystem>

#include "harness/settings/harness_axes.h"
#include "harness/passes/pass.h"
#include "ldm_impls/ldm_structure.h"
#include "harness/scene/scene_loader.h"
#include "harness/util/enum_names.h"
#include "harness/util/error.h"

namespace ldm {

constexpr EnumNames<RepetitionIsolation, 2> kRepetitionIsolationNames{
    {{RepetitionIsolation::Context, "context"}, {RepetitionIsolation::Process, "process"}}};

const char* repetition_isolation_name(RepetitionIsolation isolation) {
  return name_of(kRepetitionIsolationNames, isolation);
}

RepetitionIsolation parse_repetition_isolation(const std::string& name) {
  if (const auto isolation = value_named(kRepetitionIsolationNames, name)) return *isolation;
  throw UserError("--isolation: '" + name + "' is not context or process");
}

std::string visibility_name(Visibility v) {
  switch (v) {
    case Visibility::Attenuated: return "attenuated";
    case Visibility::Unattenuated: return "unattenuated";
    default: return "scene";
  }
}

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

namespace {

// The comma list of a --param value, each item checked against the owner's declaration and
// made canonical ("--param ppfla:k=4,08" -> {"4", "8"}).
std::vector<std::string> parameter_values(const std::string& owner, const AxisSpec& spec,
                                          const std::string& list) {
  std::vector<std::string> values;
  for (size_t start = 0;;) {
    const size_t comma = list.find(',', start);
    const std::string item = list.substr(start, comma == std::string::npos ? comma : comma - start);
    const std::string where = "--param " + owner + ":" + spec.key + "=" + list;
    if (item.empty()) throw UserError(where + ": empty item in the comma list");
    const std::string canonical = canonical_axis_value(spec, item, where);
    if (std::find(values.begin(), values.end(), canonical) != values.end())
      throw UserError(where + ": " + canonical + " appears twice");
    values.push_back(canonical);
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  return values;
}

using Dimension = std::pair<std::string, std::vector<std::string>>;

// The parameters of `owner` the run gives, as dimensions "owner:key" -> values.
void add_parameter_dimensions(const RunSettings& s, const std::string& owner,
                              const std::vector<AxisSpec>& declared, std::vector<Dimension>& dims) {
  const auto given = s.structure_params.find(owner);
  if (given == s.structure_params.end()) return;
  for (const auto& [key, list] : given->second) {
    const AxisSpec* spec = find_axis(declared, key);
    if (!spec) {
      std::string known;
      for (const auto& d : declared)
        if (d.pass_parameter.empty()) known += (known.empty() ? "" : ", ") + d.key;
      throw UserError("--param " + owner + ":" + key + ": " + owner + " has no parameter '" + key +
                      "' (its parameters: " + (known.empty() ? "none" : known) + ")");
    }
    if (!spec->pass_parameter.empty()) {
      const HarnessAxis* axis = nullptr;
      for (const auto& a : harness_axes())
        if (a.spec.pass_parameter == key) axis = &a;
      throw UserError("--param " + owner + ":" + key + ": set it with " +
                      (axis ? long_flag(axis->spec.flags) : std::string("its harness axis")) +
                      " (an axis of every pass that reads it)");
    }
    dims.emplace_back(owner + ":" + key, parameter_values(owner, *spec, list));
  }
}

}  // namespace

std::vector<Configuration> expand_configurations(const RunSettings& s) {
  check_scene_names_are_distinct(s.scenes);
  std::vector<Configuration> out;
  const auto& axes = harness_axes();
  for (const auto& scene : s.scenes)
    for (const auto& pass : s.passes) {
      // A peer that reads no LDM (HBAO) is one configuration per scene and setting: the
      // structure and every LDM-only axis (N, R_LDM, trace, sizing...) do not apply to it.
      const bool ldm = make_pass(pass, StructureParams())->requirements().needs_structure;
      const std::vector<AxisSpec> pass_declared = pass_parameters(pass);
      const std::vector<std::string> structures = ldm ? s.structures : std::vector<std::string>{""};
      for (const auto& structure : structures) {
        // The product's dimensions, the first slowest: the structure's parameters, the
        // harness axes that apply, the pass's parameters. An axis without values (no
        // --d-max) has none in the configuration: its default or the scene's applies.
        std::vector<Dimension> dims;
        if (ldm) add_parameter_dimensions(s, structure, structure_parameters(structure), dims);
        for (const HarnessAxis& axis : axes) {
          const std::string& key = axis.spec.key;
          if (key == "scenes" || key == "passes" || key == "structures") continue;
          if (axis.spec.ldm_only && !ldm) continue;
          // An AO setting a pass does not read is not its axis (HBAO has no trace).
          if (!axis.spec.pass_parameter.empty() && !find_axis(pass_declared, axis.spec.pass_parameter)) continue;
          std::vector<std::string> values = axis_list(s, axis);
          if (!values.empty()) dims.emplace_back(key, std::move(values));
        }
        add_parameter_dimensions(s, pass, pass_declared, dims);
        std::vector<size_t> index(dims.size(), 0);
        for (bool more = true; more;) {
          AxisValues values = {{"scenes", scene}, {"passes", pass}};
          if (ldm) values["structures"] = structure;
          for (size_t d = 0; d < dims.size(); ++d) values[dims[d].first] = dims[d].second[index[d]];
          Configuration c = configuration_of(values);
          c.id_ = configuration_id(values, {});
          out.push_back(std::move(c));
          // Odometer: the last dimension fastest.
          more = false;
          for (size_t d = dims.size(); d-- > 0;) {
            if (++index[d] < dims[d].second.size()) {
              more = true;
              break;
            }
            index[d] = 0;
          }
        }
      }
    }
  return out;
}

}  // namespace ldm
