#include "harness/settings/axis_options.h"

#include <algorithm>
#include <cctype>
#include <cstdio>

#include "harness/settings/harness_axes.h"
#include "harness/util/error.h"
#include "harness/util/text.h"
#include "ldm_impls/ldm_structure.h"

namespace ldm {
namespace {

std::string format_g(double x) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%g", x);
  return buffer;
}

// The help text of a harness axis's option, from its declaration.
std::string axis_help(const AxisSpec& spec) {
  std::string help = spec.description;
  if (help.empty()) help = spec.display_name();
  help[0] = char(std::toupper(static_cast<unsigned char>(help[0])));
  if (!spec.unit.empty()) help += " [" + spec.unit + "]";
  if (spec.kind == AxisKind::Choice) help += " (" + joined(axis_choices(spec)) + ")";
  if (spec.kind == AxisKind::UInt || spec.kind == AxisKind::Real)
    help += " in [" + format_g(spec.min) + ", " + format_g(spec.max) + "]";
  if (spec.list) help += "; a comma list is an axis";
  if (!spec.default_value.empty()) help += " (default: " + spec.default_value + ")";
  else if (!spec.default_note.empty()) help += " (default: " + spec.default_note + ")";
  return help;
}

// The canonical values of an axis's option: every item checked by its declaration,
// duplicates refused, "all" structures expanded.
std::vector<std::string> axis_values_given(const AxisSpec& spec, const std::vector<std::string>& texts) {
  const std::string option = long_flag(spec.flags);
  if (spec.kind == AxisKind::Choice) {  // every unknown name of the list at once
    const auto names = axis_choices(spec);
    std::vector<std::string> unknown;
    for (const std::string& text : texts)
      if (std::find(names.begin(), names.end(), text) == names.end() &&
          !(spec.key == "structures" && text == "all"))
        unknown.push_back("'" + text + "'");
    if (unknown.size() > 1) {
      std::string list;
      for (size_t i = 0; i < unknown.size(); ++i) list += (i ? ", " : "") + unknown[i];
      std::string known;
      for (size_t i = 0; i < names.size(); ++i) known += (i ? ", " : "") + names[i];
      throw UserError(option + ": unknown " + spec.display_name() + "s " + list + " (known: " + known + ")");
    }
  }
  std::vector<std::string> values;
  for (const std::string& text : texts) {
    std::vector<std::string> items = {text};
    if (spec.key == "structures" && text == "all") items = structure_names();
    for (const std::string& item : items) {
      const std::string canonical = canonical_axis_value(spec, item, option);
      if (std::find(values.begin(), values.end(), canonical) != values.end()) {
        if (text == "all") continue;
        throw UserError(option + ": " + canonical + " appears twice");
      }
      values.push_back(canonical);
    }
  }
  return values;
}
}  // namespace

void add_axis_options(CLI::App* command, AxisOptions& axes) {
  for (const HarnessAxis& axis : harness_axes()) {
    const AxisSpec& spec = axis.spec;
    if (spec.flags.empty()) continue;
    CLI::Option* option = command->add_option(spec.flags, axes.texts[spec.key], axis_help(spec));
    if (spec.list)
      option->delimiter(',');
    else
      option->expected(1);
    axes.options[spec.key] = option;
  }
}

void apply_axis_options(const AxisOptions& axes, RunSettings& settings) {
  for (const HarnessAxis& axis : harness_axes()) {
    if (!axes.given(axis.spec.key)) continue;
    set_axis_list(settings, axis, axis_values_given(axis.spec, axes.texts.at(axis.spec.key)));
  }
}

}  // namespace ldm
