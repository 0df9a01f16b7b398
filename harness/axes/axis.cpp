#include "harness/axes/axis.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <utility>

#include "harness/util/error.h"
#include "harness/util/text.h"

namespace ldm {
namespace {

[[noreturn]] void refuse(const std::string& where, const std::string& what) {
  throw UserError(where + ": " + what);
}

// A decimal integer of digits only (no sign, no spaces, at most 19 digits).
bool parse_unsigned(const std::string& text, uint64_t& value) {
  if (text.empty() || text.size() > 19 || text.find_first_not_of("0123456789") != std::string::npos)
    return false;
  value = std::strtoull(text.c_str(), nullptr, 10);
  return true;
}

}  // namespace

std::string shortest_text(double value, bool as_float) {
  char buffer[48];
  for (int digits = 1; digits <= 17; ++digits) {
    std::snprintf(buffer, sizeof buffer, "%.*g", digits, value);
    const double back = std::strtod(buffer, nullptr);
    if (as_float ? float(back) == float(value) : back == value) return buffer;
  }
  std::snprintf(buffer, sizeof buffer, "%.17g", value);
  return buffer;
}

std::string axis_range_text(const AxisSpec& spec) {
  // Integral bounds in full ("100000", not "1e+05"); canonical values keep shortest_text,
  // since ids and sweep keys are made of them.
  const auto bound = [](double x) {
    if (x == std::floor(x) && std::abs(x) < 1e16) return std::to_string(static_cast<long long>(x));
    return shortest_text(x, double(float(x)) == x);  // FLT_MAX as 3.4028235e+38
  };
  return "[" + bound(spec.min) + ", " + bound(spec.max) + "]";
}

const char* axis_kind_name(AxisKind kind) {
  switch (kind) {
    case AxisKind::Choice: return "choice";
    case AxisKind::UInt: return "uint";
    case AxisKind::Real: return "real";
    case AxisKind::Bool: return "bool";
    case AxisKind::ImageSize: return "image_size";
    default: return "text";
  }
}

std::vector<std::string> axis_choices(const AxisSpec& spec) {
  return spec.dynamic_choices ? spec.dynamic_choices() : spec.choices;
}

double axis_real_used(const AxisSpec& spec, double value) {
  return spec.real_is_double ? value : double(float(value));
}

std::string axis_real_problem(const AxisSpec& spec, double value, const std::string& text) {
  // Checked as the number the run uses: a float on the GPU reads 1e39 as inf, 1e-50 as 0.
  const double used = axis_real_used(spec, value);
  if (std::isfinite(used) && used >= spec.min && used <= spec.max) return "";
  return (text.empty() ? shortest_text(value, false) : text) + " reads as " + shortest_text(used, false) +
         (spec.real_is_double ? "" : " in a 32-bit float") + "; it must lie in " + axis_range_text(spec);
}

std::string canonical_axis_value(const AxisSpec& spec, const std::string& text,
                                 const std::string& where) {
  const std::string name = spec.display_name();
  switch (spec.kind) {
    case AxisKind::Text:
      if (text.empty()) refuse(where, "expected a non-empty " + name);
      if (spec.list && text.find(',') != std::string::npos)
        refuse(where, "a comma in a " + name + " (commas separate the values of a list)");
      return text;
    case AxisKind::Choice: {
      const auto names = axis_choices(spec);
      if (std::find(names.begin(), names.end(), text) == names.end())
        refuse(where, "unknown " + name + " '" + text + "' (known: " + joined(names) + ")");
      return text;
    }
    case AxisKind::UInt: {
      uint64_t value = 0;
      if (!parse_unsigned(text, value))
        refuse(where, name + " '" + text + "' is not a non-negative integer");
      if (double(value) < spec.min || double(value) > spec.max)
        refuse(where, name + " " + text + " is out of range " + axis_range_text(spec));
      return std::to_string(value);
    }
    case AxisKind::Real: {
      const char* begin = text.c_str();
      char* end = nullptr;
      errno = 0;
      const double value = std::strtod(begin, &end);
      if (text.empty() || *end != '\0' || std::isspace(static_cast<unsigned char>(text[0])))
        refuse(where, name + " '" + text + "' is not a number");
      if (const std::string problem = axis_real_problem(spec, value, text); !problem.empty())
        refuse(where, name + " " + problem);
      return shortest_text(axis_real_used(spec, value), !spec.real_is_double);
    }
    case AxisKind::Bool: {
      if (text == "true" || text == "1" || text == "on" || text == "yes") return "true";
      if (text == "false" || text == "0" || text == "off" || text == "no") return "false";
      refuse(where, name + " '" + text + "' is not true or false");
    }
    case AxisKind::ImageSize: {
      uint64_t w = 0, h = 0;
      const auto x = text.find('x');
      const bool ok = x == std::string::npos
                          ? parse_unsigned(text, w) && (h = w, true)
                          : parse_unsigned(text.substr(0, x), w) && parse_unsigned(text.substr(x + 1), h);
      if (!ok) refuse(where, "expected an image size WIDTHxHEIGHT (e.g. 64x48) or one integer, got '" + text + "'");
      for (uint64_t side : {w, h})
        if (double(side) < spec.min || double(side) > spec.max)
          refuse(where, "image side " + std::to_string(side) + " is out of range " + axis_range_text(spec));
      return std::to_string(w) + "x" + std::to_string(h);
    }
  }
  refuse(where, "unhandled axis kind");
}

std::string axis_text_of_json(const nlohmann::json& value, const std::string& where) {
  if (value.is_string()) return value.get<std::string>();
  if (value.is_boolean()) return value.get<bool>() ? "true" : "false";
  if (value.is_number_unsigned()) return std::to_string(value.get<uint64_t>());
  if (value.is_number_integer()) return std::to_string(value.get<int64_t>());
  if (value.is_number_float()) {
    if (!std::isfinite(value.get<double>())) refuse(where, "not a finite number");
    return shortest_text(value.get<double>(), false);
  }
  refuse(where, std::string("expected a string, number or boolean, got ") +
                    (value.is_number() ? "a number" : std::string("a ") + value.type_name()));
}

nlohmann::json axis_json_of_text(const AxisSpec& spec, const std::string& canonical) {
  switch (spec.kind) {
    case AxisKind::UInt: return std::strtoull(canonical.c_str(), nullptr, 10);
    case AxisKind::Real: return std::strtod(canonical.c_str(), nullptr);
    case AxisKind::Bool: return canonical == "true";
    default: return canonical;
  }
}

nlohmann::json axis_spec_json(const AxisSpec& spec) {
  nlohmann::json j = {{"name", spec.qualified()},
                      {"key", spec.key},
                      {"owner", spec.owner},
                      {"label", spec.display_name()},
                      {"kind", axis_kind_name(spec.kind)},
                      {"list", spec.list},
                      {"identity", spec.identity},
                      {"ldm_only", spec.ldm_only},
                      {"unit", spec.unit},
                      {"description", spec.description},
                      {"column", spec.column}};
  if (!spec.flags.empty()) j["flags"] = spec.flags;
  if (spec.kind == AxisKind::UInt || spec.kind == AxisKind::Real || spec.kind == AxisKind::ImageSize) {
    j["min"] = spec.min;
    j["max"] = spec.max;
  }
  if (spec.kind == AxisKind::Choice) j["choices"] = axis_choices(spec);
  if (!spec.default_value.empty()) j["default"] = spec.default_value;
  if (!spec.default_note.empty()) j["default_note"] = spec.default_note;
  if (!spec.pass_parameter.empty()) j["pass_parameter"] = spec.pass_parameter;
  return j;
}

const AxisSpec* find_axis(const std::vector<AxisSpec>& specs, const std::string& key) {
  for (const auto& s : specs)
    if (s.key == key) return &s;
  return nullptr;
}

std::string long_flag(const std::string& flags) {
  std::string best;
  size_t start = 0;
  while (start <= flags.size()) {
    const size_t comma = flags.find(',', start);
    const std::string name = flags.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
    if (best.empty() || name.rfind("--", 0) == 0) best = name;
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  return best;
}

std::optional<std::string> axis_text(const AxisValues& values, const std::string& key) {
  const auto it = values.find(key);
  if (it == values.end()) return std::nullopt;
  return it->second;
}

std::optional<double> axis_real(const AxisValues& values, const std::string& key) {
  const std::optional<std::string> text = axis_text(values, key);
  if (!text) return std::nullopt;
  size_t used = 0;
  double value = 0;
  try {
    value = std::stod(*text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used == 0 || used != text->size())
    throw std::logic_error("axis " + key + ": \"" + *text + "\" is not a number");
  return value;
}

std::optional<uint64_t> axis_uint(const AxisValues& values, const std::string& key) {
  const std::optional<std::string> text = axis_text(values, key);
  if (!text) return std::nullopt;
  uint64_t value = 0;
  if (!parse_unsigned(*text, value))
    throw std::logic_error("axis " + key + ": \"" + *text + "\" is not an unsigned integer");
  return value;
}

AxisSpec numeric_parameter(std::string key, AxisKind kind, double min, double max,
                           std::string default_value, std::string unit, std::string description,
                           std::string column) {
  AxisSpec p;
  p.key = std::move(key);
  p.kind = kind;
  p.min = min;
  p.max = max;
  p.default_value = std::move(default_value);
  p.unit = std::move(unit);
  p.description = std::move(description);
  p.column = std::move(column);
  return p;
}

AxisSpec choice_parameter(std::string key, std::vector<std::string> choices,
                          std::string default_value, std::string description,
                          std::string column) {
  AxisSpec p;
  p.key = std::move(key);
  p.kind = AxisKind::Choice;
  p.choices = std::move(choices);
  p.default_value = std::move(default_value);
  p.description = std::move(description);
  p.column = std::move(column);
  return p;
}

}  // namespace ldm
