#include "harness/settings/run_command_line.h"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <functional>

#include <nlohmann/json.hpp>

#include "harness/settings/harness_axes.h"

namespace ldm {
namespace {

// Enough digits that the float (or double) read back is the one written.
std::string exact(double value, int digits) {
  char buffer[48];
  std::snprintf(buffer, sizeof buffer, "%.*g", digits, value);
  return buffer;
}

template <typename T, typename Name>
std::string joined(const std::vector<T>& values, Name name) {
  std::string out;
  for (const auto& v : values) out += (out.empty() ? "" : ",") + name(v);
  return out;
}

// The shortest text that reads back as the same double (0.03, not 0.029999999999999999).
std::string shortest(double value) {
  for (int digits = 1; digits < 17; ++digits) {
    const std::string text = exact(value, digits);
    if (std::strtod(text.c_str(), nullptr) == value) return text;
  }
  return exact(value, 17);
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
  add("--repetitions", std::to_string(s.repetitions));
  add("--isolation", repetition_isolation_name(s.isolation));
  add("--time-target", shortest(s.precision.target));
  add("--time-cap", shortest(s.precision.cap_seconds));
  add("--clock-warmup", shortest(s.precision.clock_warmup_seconds));
  add("--max-frames", std::to_string(s.precision.max_frames));
  add("--timer", s.timer);
  add("--verify", s.verify);
  if (!s.reference.enabled) {
    line += " --no-reference";
  } else {
    add("--reference-spp", std::to_string(s.reference.spp.spp_per_half));
    add("--reference-noise", exact(s.reference.spp.target_noise_mse, 17));
    add("--reference-max-spp", std::to_string(s.reference.spp.max_spp_per_half));
    add("--reference-seed", std::to_string(s.reference.seed));
    if (!s.reference.cache_dir.empty()) add("--cache-dir", s.reference.cache_dir);
  }
  if (!s.write_images) line += " --no-images";
  if (!s.count_work) line += " --no-work";
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

  json reference = {{"enabled", s.reference.enabled}};
  if (s.reference.enabled) {
    reference["spp"] = s.reference.spp.spp_per_half;
    reference["noise"] = s.reference.spp.target_noise_mse;
    reference["max_spp"] = s.reference.spp.max_spp_per_half;
    reference["seed"] = s.reference.seed;
  }
  json file = json::object();
  if (!description.empty()) file["description"] = description;
  file["axes"] = axes;
  const json timing = {{"repetitions", s.repetitions},
                       {"isolation", repetition_isolation_name(s.isolation)},
                       {"target", s.precision.target},
                       {"cap_s", s.precision.cap_seconds},
                       {"clock_warmup_s", s.precision.clock_warmup_seconds},
                       {"max_frames", s.precision.max_frames}};
  file["settings"] = {{"reference", reference}, {"images", s.write_images}, {"work", s.count_work}, {"timer", s.timer},
                      {"verify", s.verify}, {"timing", timing}};
  return file.dump(2) + "\n";
}

}  // namespace ldm
