#include "harness/settings/run_setting_table.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "harness/records/harness_columns.h"

namespace ldm {
namespace {

using Kind = SettingRule::Kind;

RunSetting flag_setting(std::string path, std::string flag, std::string help, SettingFieldOf<bool> field,
                        std::string written_when = "") {
  RunSetting s;
  s.path = std::move(path), s.flag = std::move(flag), s.help = std::move(help);
  s.kind = Kind::Flag, s.field = field, s.written_when = std::move(written_when);
  return s;
}

template <typename Field>
RunSetting number_setting(std::string path, std::string flag, std::string help, Kind kind, Field field,
                          double min, double max, std::string written_when = "") {
  RunSetting s;
  s.path = std::move(path), s.flag = std::move(flag), s.help = std::move(help);
  s.kind = kind, s.field = field, s.min = min, s.max = max, s.written_when = std::move(written_when);
  return s;
}

RunSetting int_setting(std::string path, std::string flag, std::string help, SettingFieldOf<int> field,
                       double min, double max) {
  return number_setting(std::move(path), std::move(flag), std::move(help), Kind::Integer, field, min, max);
}

RunSetting uint_setting(std::string path, std::string flag, std::string help, SettingFieldOf<uint32_t> field,
                        double min, double max, std::string written_when = "") {
  return number_setting(std::move(path), std::move(flag), std::move(help), Kind::Integer, field, min, max,
                        std::move(written_when));
}

// A field of the timing precision, carried to the record (its column).
RunSetting precision_setting(std::string path, std::string flag, std::string help, double TimePrecision::*field,
                             double min, double max, const Column& column) {
  RunSetting s = number_setting(std::move(path), std::move(flag), std::move(help), Kind::Real, field, min, max);
  s.column = &column;
  return s;
}

template <typename Field>
RunSetting choice_setting(std::string path, std::string flag, std::string help, Field field,
                          std::vector<std::string> choices) {
  RunSetting s;
  s.path = std::move(path), s.flag = std::move(flag), s.help = std::move(help);
  s.kind = Kind::Choice, s.field = field, s.choices = std::move(choices);
  return s;
}

std::vector<RunSetting> declared_settings() {
  std::vector<RunSetting> t;
  // The timing protocol (harness/measure/frame_stop_rule.h, harness/measuring/repetitions.h).
  t.push_back(int_setting("timing.repetitions", "--repetitions",
                          "Independent repetitions of every configuration, each in a fresh GL context, "
                          "round robin over the configurations; the record's interval is then over the "
                          "repetitions (what `ldmbench compare` needs to judge time)",
                          [](RunSettings& s) -> int& { return s.repetitions; }, 1, 1000));
  t.push_back(choice_setting("timing.isolation", "--isolation",
                             "What keeps repetitions independent: context (a fresh GL context per round, "
                             "in this process) or process (a process of its own per repetition)",
                             SettingText{[](const RunSettings& s) -> std::string { return repetition_isolation_name(s.isolation); },
                                         [](RunSettings& s, const std::string& text) { s.isolation = parse_repetition_isolation(text); }},
                             {"context", "process"}));
  t.push_back(precision_setting("timing.target", "--time-target",
                                "Measure frames until the 95% interval of the median (order statistics) is "
                                "within this relative half-width for build and frame (0.03: +-3%), or "
                                "--time-cap; 0: exactly --frames",
                                &TimePrecision::target, 0, 1, columns::kTimeTarget));
  t.push_back(precision_setting("timing.cap_s", "--time-cap",
                                "Seconds of measured frames per repetition after which it stops, target "
                                "met or not (a miss is a warning in status_detail)",
                                &TimePrecision::cap_seconds, 0, 86400, columns::kTimeCapS));
  t.push_back(precision_setting("timing.clock_warmup_s", "--clock-warmup",
                                "NVIDIA: after the warm-up frames, more until the GPU's SM clock reaches its "
                                "working level (90% of its maximum, or steady at 75%), for at most this many "
                                "seconds (nvidia-smi; elsewhere nothing is added); 0: off",
                                &TimePrecision::clock_warmup_seconds, 0, 600, columns::kTimeClockWarmupS));
  t.push_back(int_setting("timing.max_frames", "--max-frames", "Measured frames per repetition, at most",
                          [](RunSettings& s) -> int& { return s.precision.max_frames; }, 1, 1000000));
  // How sub-passes are timed and builds checked.
  t.push_back(choice_setting("timer", "--timer",
                             "Sub-pass timing: gl_timestamp (GPU timer queries), fenced_wall_clock "
                             "(glFinish around each sub-pass), or auto (wall clock on software "
                             "rasterisers such as llvmpipe, whose timestamps miss most of the work)",
                             SettingFieldOf<std::string>([](RunSettings& s) -> std::string& { return s.timer; }),
                             {"auto", "gl_timestamp", "fenced_wall_clock"}));
  t.push_back(choice_setting("verify", "--verify",
                             "How much of each build is checked: sampled (in full after the first build "
                             "and after the sizing policy changed the storage, otherwise one 64-pixel "
                             "block in 32, rotating) or every (in full after every build)",
                             SettingFieldOf<std::string>([](RunSettings& s) -> std::string& { return s.verify; }),
                             {"every", "sampled"}));
  // The reference the records are scored against (harness/reference/reference_settings.h);
  // its settings are written only with the reference on.
  t.push_back(flag_setting("reference.enabled", "--no-reference",
                           "Skip the path-traced reference and the image metrics",
                           [](RunSettings& s) -> bool& { return s.reference.enabled; }));
  t.push_back(uint_setting("reference.spp", "--reference-spp",
                           "Reference samples per pixel per half (0: double until the noise target)",
                           [](RunSettings& s) -> uint32_t& { return s.reference.spp.spp_per_half; }, 0,
                           double(1u << 20), "reference.enabled"));
  RunSetting noise = number_setting("reference.noise", "--reference-noise",
                                    "Noise target of the automatic spp rule: the reference's expected MSE", Kind::Real,
                                    SettingFieldOf<double>([](RunSettings& s) -> double& { return s.reference.spp.target_noise_mse; }),
                                    0, 0, "reference.enabled");
  noise.positive = true;
  t.push_back(noise);
  t.push_back(uint_setting("reference.max_spp", "--reference-max-spp",
                           "Cap of the automatic spp rule (samples per pixel per half)",
                           [](RunSettings& s) -> uint32_t& { return s.reference.spp.max_spp_per_half; }, 1,
                           double(1u << 20), "reference.enabled"));
  RunSetting seed = number_setting("reference.seed", "--reference-seed", "Seed of the reference (halves: s, s+1)",
                                   Kind::Integer,
                                   SettingFieldOf<uint64_t>([](RunSettings& s) -> uint64_t& { return s.reference.seed; }),
                                   0, 4294967295.0, "reference.enabled");
  seed.cli_range = false;
  t.push_back(seed);
  // What is written beside the records, and the untimed work replay.
  t.push_back(flag_setting("images", "--no-images", "Do not write images",
                           [](RunSettings& s) -> bool& { return s.write_images; }));
  t.push_back(flag_setting("work", "--no-work",
                           "Skip the untimed counting replay: no work_* columns (only to measure what counting costs)",
                           [](RunSettings& s) -> bool& { return s.count_work; }));
  return t;
}

// A setting's field in const settings (the table's accessors take them mutable).
RunSettings& mutable_settings(const RunSettings& s) { return const_cast<RunSettings&>(s); }

}  // namespace

std::string RunSetting::group() const {
  const auto dot = path.find('.');
  return dot == std::string::npos ? std::string() : path.substr(0, dot);
}

std::string RunSetting::key() const {
  const auto dot = path.find('.');
  return dot == std::string::npos ? path : path.substr(dot + 1);
}

const std::vector<RunSetting>& run_setting_table() {
  static const std::vector<RunSetting> table = declared_settings();
  return table;
}

const RunSetting* find_run_setting(const std::string& path) {
  for (const auto& s : run_setting_table())
    if (s.path == path) return &s;
  return nullptr;
}

std::string shortest_number_text(double value) {
  char buffer[48];
  for (int digits = 1; digits <= 17; ++digits) {
    std::snprintf(buffer, sizeof buffer, "%.*g", digits, value);
    if (digits == 17 || std::strtod(buffer, nullptr) == value) break;
  }
  return buffer;
}

nlohmann::json run_setting_json(const RunSetting& setting, const RunSettings& settings) {
  RunSettings& s = mutable_settings(settings);
  return std::visit(
      [&s](const auto& field) -> nlohmann::json {
        using F = std::decay_t<decltype(field)>;
        if constexpr (std::is_same_v<F, SettingText>) return field.get(s);
        else if constexpr (std::is_same_v<F, double TimePrecision::*>) return s.precision.*field;
        else return field(s);
      },
      setting.field);
}

std::string run_setting_text(const RunSetting& setting, const RunSettings& settings) {
  const nlohmann::json v = run_setting_json(setting, settings);
  if (v.is_string()) return v.get<std::string>();
  if (v.is_number_float()) return shortest_number_text(v.get<double>());
  return v.dump();  // integers, true/false
}

void set_run_setting_json(const RunSetting& setting, RunSettings& s, const nlohmann::json& value) {
  std::visit(
      [&s, &value](const auto& field) {
        using F = std::decay_t<decltype(field)>;
        if constexpr (std::is_same_v<F, SettingText>) {
          field.set(s, value.get<std::string>());
        } else if constexpr (std::is_same_v<F, double TimePrecision::*>) {
          s.precision.*field = value.get<double>();
        } else {
          using T = std::remove_reference_t<decltype(field(s))>;
          // Integers as a sweep file's parser checked them: unsigned, within the range.
          if constexpr (std::is_same_v<T, int>) field(s) = int(value.get<uint32_t>());
          else field(s) = value.get<T>();
        }
      },
      setting.field);
}

bool run_setting_written(const RunSetting& setting, const RunSettings& settings) {
  if (setting.written_when.empty()) return true;
  const RunSetting* when = find_run_setting(setting.written_when);
  return !when || run_setting_json(*when, settings) == nlohmann::json(true);
}

std::vector<SettingRule> run_setting_rules() {
  std::vector<SettingRule> rules;
  for (const auto& s : run_setting_table()) {
    SettingRule r;
    r.path = s.path, r.kind = s.kind, r.min = s.min, r.max = s.max, r.positive = s.positive;
    r.choices = s.choices;
    rules.push_back(std::move(r));
  }
  return rules;
}

}  // namespace ldm
