#include "harness/cli/cli_model.h"

#include <algorithm>

#include "harness/settings/axis_registry.h"
#include "harness/settings/harness_axes.h"
#include "harness/scene/generators.h"

namespace ldm::cli {
namespace {

// The names a CLI11 IsMember check accepts, as its type name shows them: "TEXT:{a,b,c}".
std::vector<std::string> member_names(const std::string& type_name) {
  const size_t open = type_name.find(":{"), close = type_name.rfind('}');
  if (open == std::string::npos || close == std::string::npos || close < open) return {};
  std::vector<std::string> names;
  const std::string list = type_name.substr(open + 2, close - open - 2);
  for (size_t start = 0; start <= list.size();) {
    const size_t comma = std::min(list.find(',', start), list.size());
    if (comma > start) names.push_back(list.substr(start, comma - start));
    start = comma + 1;
  }
  return names;
}

// The values an axis accepts as completions: a choice's names ("all" structures too), a
// boolean's, the built-in scenes (a scene may also be a file).
std::vector<std::string> axis_values(const AxisSpec& spec) {
  std::vector<std::string> values;
  if (spec.kind == AxisKind::Choice) values = axis_choices(spec);
  if (spec.kind == AxisKind::Bool) values = {"true", "false"};
  if (spec.key == "structures") values.push_back("all");  // axis_options.cpp expands it
  if (spec.key == "scenes")
    for (const auto& g : scene_generators()) values.push_back(g.name);
  return values;
}

const HarnessAxis* axis_of_option(const CLI::Option& option) {
  for (const HarnessAxis& axis : harness_axes())
    if (!axis.spec.flags.empty())
      for (const std::string& name : option.get_lnames())
        if (long_flag(axis.spec.flags) == "--" + name) return &axis;
  return nullptr;
}

OptionModel option_model(const CLI::Option& option) {
  OptionModel m;
  for (const auto& name : option.get_lnames()) m.names.push_back("--" + name);
  for (const auto& name : option.get_snames()) m.names.push_back("-" + name);
  if (m.names.empty()) m.positional = option.get_name();
  if (option.get_items_expected_max() > 0) {
    const std::string type = option.get_type_name();
    m.value_name = type.substr(0, type.find(':'));
    if (m.value_name.empty()) m.value_name = "VALUE";
    m.values = member_names(type);
  }
  m.description = option.get_description();
  m.default_value = option.get_default_str();
  m.required = option.get_required();
  if (const HarnessAxis* axis = axis_of_option(option)) {
    m.list = axis->spec.list;
    m.values = axis_values(axis->spec);
    m.files = axis->spec.key == "scenes";
  } else if (m.takes_value()) {
    m.files = m.values.empty() && m.value_name == "TEXT";  // --out, --cache-dir, a run folder...
  }
  return m;
}

}  // namespace

std::vector<const CLI::App*> subcommands_of(const CLI::App& app) {
  std::vector<const CLI::App*> out;
  for (const CLI::App* sub : app.get_subcommands([](const CLI::App*) { return true; }))
    out.push_back(sub);
  return out;
}

CommandModel command_model(const CLI::App& command) {
  CommandModel m;
  m.name = command.get_parent() ? command.get_name() : "";
  m.description = command.get_description();
  m.footer = command.get_footer();
  for (const CLI::Option* option : command.get_options()) {
    OptionModel o = option_model(*option);
    (o.positional.empty() ? m.options : m.positionals).push_back(std::move(o));
  }
  return m;
}

std::vector<ParameterModel> parameter_models() {
  std::vector<ParameterModel> out;
  for (const AxisSpec& spec : registered_axes())
    if (spec.owner != "harness") out.push_back({spec.qualified(), axis_values(spec), spec.description});
  return out;
}

std::string closest_name(const std::string& given, const std::vector<std::string>& known) {
  const auto distance = [](const std::string& a, const std::string& b) {
    std::vector<size_t> row(b.size() + 1);
    for (size_t j = 0; j <= b.size(); ++j) row[j] = j;
    for (size_t i = 1; i <= a.size(); ++i) {
      size_t diagonal = row[0];
      row[0] = i;
      for (size_t j = 1; j <= b.size(); ++j) {
        const size_t above = row[j];
        row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] != b[j - 1])});
        diagonal = above;
      }
    }
    return row[b.size()];
  };
  std::string best;
  // A prefix first ("struct" -> structures), the shortest of them ("comp" -> compare).
  for (const std::string& name : known)
    if (given.size() >= 2 && name.rfind(given, 0) == 0 && (best.empty() || name.size() < best.size()))
      best = name;
  if (!best.empty()) return best;
  size_t best_distance = 0;
  for (const std::string& name : known) {
    const size_t d = distance(given, name);
    if (d <= std::max<size_t>(1, name.size() / 3) && (best.empty() || d < best_distance)) {
      best = name;
      best_distance = d;
    }
  }
  return best;
}

}  // namespace ldm::cli
