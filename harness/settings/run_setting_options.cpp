#include "harness/settings/run_setting_options.h"

#include <stdexcept>
#include <type_traits>
#include <variant>

#include "harness/settings/run_setting_table.h"

namespace ldm {

// One option per run-wide setting, in the table's order: a flag turns its setting off
// (!--no-images); a number is checked by its range, typed as its field (so that the help
// reads INT, UINT or FLOAT), a choice by its names.
void add_run_setting_options(CLI::App* command, RunSettings& s, RunSettingOptions& options) {
  for (const RunSetting& setting : run_setting_table()) {
    CLI::Option* option = nullptr;
    std::visit(
        [&](const auto& field) {
          using F = std::decay_t<decltype(field)>;
          if constexpr (std::is_same_v<F, SettingFieldOf<bool>>) {
            command->add_flag("!" + setting.flag, field(s), setting.help);
          } else if constexpr (std::is_same_v<F, SettingText>) {
            std::string& text = options.texts[setting.path];
            text = field.get(s);
            option = command->add_option(setting.flag, text, setting.help);
          } else {
            auto& value = [&]() -> auto& {
              if constexpr (std::is_same_v<F, double TimePrecision::*>) return s.precision.*field;
              else return field(s);
            }();
            using T = std::remove_reference_t<decltype(value)>;
            option = command->add_option(setting.flag, value, setting.help);
            if constexpr (std::is_arithmetic_v<T>) {
              if (setting.positive) option->check(CLI::PositiveNumber);
              else if (setting.cli_range) option->check(CLI::Range(T(setting.min), T(setting.max)));
            }
          }
        },
        setting.field);
    if (!option) continue;
    if (setting.kind == SettingRule::Kind::Choice) option->check(CLI::IsMember(setting.choices));
    option->capture_default_str();
  }
}

void apply_run_setting_options(const RunSettingOptions& options, RunSettings& settings) {
  for (const RunSetting& setting : run_setting_table())
    if (const auto* text = std::get_if<SettingText>(&setting.field)) {
      const auto given = options.texts.find(setting.path);
      if (given != options.texts.end()) text->set(settings, given->second);
    }
}

void add_run_setting_overrides(CLI::App* command, RunSettingOverrides& overrides,
                               const std::vector<std::string>& paths, const std::string& default_from) {
  for (const std::string& path : paths) {
    const RunSetting* setting = find_run_setting(path);
    if (!setting || setting->kind == SettingRule::Kind::Flag)
      throw std::logic_error("no run-wide setting '" + path + "' to override");
    CLI::Option* option = command->add_option(
        setting->flag, overrides.given[path],
        setting->help + " (default: " + default_from + "'s settings." + path + ")");
    if (setting->kind == SettingRule::Kind::Choice) option->check(CLI::IsMember(setting->choices));
    if (setting->kind == SettingRule::Kind::Integer) option->type_name("INT");
    if (setting->kind == SettingRule::Kind::Real) option->type_name("FLOAT");
    if (setting->kind == SettingRule::Kind::Integer && setting->cli_range)
      option->check(CLI::Range(int64_t(setting->min), int64_t(setting->max)));
    if (setting->kind == SettingRule::Kind::Real)
      option->check(setting->positive ? CLI::Validator(CLI::PositiveNumber) : CLI::Range(setting->min, setting->max));
    overrides.options.push_back(option);
  }
}

void apply_run_setting_overrides(const RunSettingOverrides& overrides, RunSettings& settings) {
  for (const auto& [path, text] : overrides.given) {
    if (text.empty()) continue;
    const RunSetting& setting = *find_run_setting(path);
    if (setting.kind == SettingRule::Kind::Integer)
      set_run_setting_json(setting, settings, nlohmann::json(uint32_t(std::stoul(text))));
    else if (setting.kind == SettingRule::Kind::Real)
      set_run_setting_json(setting, settings, nlohmann::json(std::stod(text)));
    else
      set_run_setting_json(setting, settings, nlohmann::json(text));
  }
}

}  // namespace ldm
