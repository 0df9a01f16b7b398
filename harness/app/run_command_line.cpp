#include "harness/app/run_command_line.h"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <functional>

#include <nlohmann/json.hpp>

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

std::string run_command_line(const RunSettings& s, const std::string& program,
                             const std::string& out_dir) {
  std::string line = shell_quoted(program) + " run";
  auto add = [&line](const std::string& option, const std::string& value) {
    line += " " + option + " " + shell_quoted(value);
  };
  auto same = [](const std::string& v) { return v; };
  add("--scene", joined(s.scenes, same));
  add("--structure", joined(s.structures, same));
  add("--pass", joined(s.passes, same));
  add("-N", joined(s.views, [](uint32_t v) { return std::to_string(v); }));
  add("-R", joined(s.resolutions, [](uint32_t v) { return std::to_string(v); }));
  add("--width", std::to_string(s.width));
  add("--height", std::to_string(s.height));
  if (!s.d_max.empty()) add("--d-max", joined(s.d_max, [](float d) { return exact(d, 9); }));
  add("--visibility", joined(s.visibility, visibility_name));
  add("--trace", joined(s.traces, ao_trace_name));
  add("--ao-estimator", joined(s.estimators, ao_estimator_name));
  add("--sizing", joined(s.sizing, [](SizingPolicy p) { return std::string(sizing_policy_name(p)); }));
  for (SizingPolicy p : s.sizing)
    if (p == SizingPolicy::Budget) add("--sizing-budget-mib", exact(s.sizing_budget_mib, 17));
  add("--sizing-initial-per-pixel", std::to_string(s.sizing_initial_per_pixel));
  if (s.normal_offset_pixels) add("--normal-offset", exact(*s.normal_offset_pixels, 9));
  // Parameters of a structure or pass not measured are left out (run refuses them).
  auto measured = [&s](const std::string& owner) {
    return std::find(s.structures.begin(), s.structures.end(), owner) != s.structures.end() ||
           std::find(s.passes.begin(), s.passes.end(), owner) != s.passes.end();
  };
  for (const auto& [owner, params] : s.structure_params)
    if (measured(owner))
      for (const auto& [key, value] : params) add("--param", owner + ":" + key + "=" + value);
  add("--frames", std::to_string(s.frames));
  add("--warmup", std::to_string(s.warmup));
  add("--repetitions", std::to_string(s.repetitions));
  add("--isolation", repetition_isolation_name(s.isolation));
  add("--time-target", shortest(s.precision.target));
  add("--time-cap", shortest(s.precision.cap_seconds));
  add("--max-frames", std::to_string(s.precision.max_frames));
  add("--timer", s.timer);
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
  if (!out_dir.empty()) add("--out", out_dir);
  return line;
}

std::string sweep_file_json(const RunSettings& s, const std::string& description) {
  using nlohmann::json;
  json axes = json::object();
  axes["scenes"] = s.scenes;
  axes["structures"] = s.structures;
  axes["passes"] = s.passes;
  axes["views"] = s.views;
  axes["r_ldm"] = s.resolutions;
  if (!s.d_max.empty()) {
    json d_max = json::array();
    for (float d : s.d_max) d_max.push_back(double(d));  // exact: every float is a double
    axes["d_max"] = d_max;
  }
  auto names = [](const auto& values, auto name) {
    json out = json::array();
    for (const auto& v : values) out.push_back(std::string(name(v)));
    return out;
  };
  axes["visibility"] = names(s.visibility, visibility_name);
  axes["trace"] = names(s.traces, ao_trace_name);
  axes["ao_estimator"] = names(s.estimators, ao_estimator_name);
  axes["sizing"] = names(s.sizing, [](SizingPolicy p) { return sizing_policy_name(p); });
  for (SizingPolicy p : s.sizing)
    if (p == SizingPolicy::Budget) axes["sizing_budget_mib"] = s.sizing_budget_mib;
  axes["sizing_initial_per_pixel"] = s.sizing_initial_per_pixel;
  if (s.normal_offset_pixels) axes["normal_offset"] = double(*s.normal_offset_pixels);
  axes["image_size"] = std::to_string(s.width) + "x" + std::to_string(s.height);
  axes["frames"] = s.frames;
  axes["warmup"] = s.warmup;
  // Parameters of a structure or pass not measured are left out, as on the command line.
  auto measured = [&s](const std::string& owner) {
    return std::find(s.structures.begin(), s.structures.end(), owner) != s.structures.end() ||
           std::find(s.passes.begin(), s.passes.end(), owner) != s.passes.end();
  };
  for (const auto& [owner, params] : s.structure_params)
    if (measured(owner))
      for (const auto& [key, value] : params) axes[owner + ":" + key] = value;

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
                       {"max_frames", s.precision.max_frames}};
  file["settings"] = {{"reference", reference}, {"images", s.write_images}, {"timer", s.timer},
                      {"timing", timing}};
  return file.dump(2) + "\n";
}

}  // namespace ldm
