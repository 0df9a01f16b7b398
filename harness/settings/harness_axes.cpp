#include "harness/settings/harness_axes.h"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <set>
#include <stdexcept>

#include "harness/passes/ao_parameters.h"
#include "harness/passes/pass.h"
#include "harness/records/harness_columns.h"
#include "harness/scene/scene_loader.h"
#include "harness/util/error.h"
#include "harness/util/text.h"
#include "ldm_impls/ldm_structure.h"

namespace ldm {
namespace {

template <typename T, typename F>
std::vector<std::string> texts(const std::vector<T>& values, F text) {
  std::vector<std::string> out;
  for (const auto& v : values) out.push_back(text(v));
  return out;
}

template <typename T, typename F>
std::vector<T> parsed(const std::vector<std::string>& values, F parse) {
  std::vector<T> out;
  for (const auto& v : values) out.push_back(parse(v));
  return out;
}

uint32_t to_u32(const std::string& v) { return uint32_t(std::strtoul(v.c_str(), nullptr, 10)); }

Visibility parse_visibility_name(const std::string& v) {
  return v == "attenuated" ? Visibility::Attenuated
         : v == "unattenuated" ? Visibility::Unattenuated : Visibility::Scene;
}

std::string value_of(const AxisValues& values, const std::string& key) {
  const auto it = values.find(key);
  return it == values.end() ? std::string() : it->second;
}

// "-d%g" of the float: the fragment ids have always had.
std::string d_fragment(const std::string& value) {
  if (value.empty()) return "";
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "-d%g", double(std::strtof(value.c_str(), nullptr)));
  return buffer;
}

// Each axis declared in one designated initializer (the fields in AxisSpec's order), as
// harness/scene/ao_axes.cpp declares the AO axes; the fields left out keep their defaults,
// which GCC 12's -Wextra would name one by one.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
std::vector<HarnessAxis> declare() {
  std::vector<HarnessAxis> axes;
  auto add = [&axes](AxisSpec spec, int id_rank, auto get, auto set, auto id) {
    HarnessAxis a;
    a.spec = std::move(spec);
    a.id_rank = id_rank;
    a.get = get;
    a.set = set;
    a.id_fragment = id;
    // A pass parameter's column is the pass's to write (its describe()).
    a.writes_column = a.spec.pass_parameter.empty();
    axes.push_back(std::move(a));
  };
  using Values = std::vector<std::string>;
  const auto none = nullptr;

  add({.key = "scenes", .label = "scene", .flags = "--scene", .default_value = "cornell",
       .description = "built-in scene (`ldmbench scenes`), scene file (scenes/README.md) or mesh file",
       .column = columns::kScene.name},
      0, [](const RunSettings& s) { return s.scenes; },
      [](RunSettings& s, const Values& v) { s.scenes = v; },
      [](const AxisValues& c, bool) { return scene_id_name(value_of(c, "scenes")); });

  add({.key = "passes", .label = "pass", .flags = "--pass", .kind = AxisKind::Choice,
       .dynamic_choices = pass_names, .default_value = "ao",
       .description = "the pass measured on each structure (a peer that reads no LDM has structure none)",
       .column = columns::kPass.name},
      2, [](const RunSettings& s) { return s.passes; },
      [](RunSettings& s, const Values& v) { s.passes = v; },
      [](const AxisValues& c, bool) { return "-" + value_of(c, "passes"); });

  add({.key = "structures", .label = "structure", .flags = "--structure", .kind = AxisKind::Choice,
       .dynamic_choices = structure_names, .default_value = "psppsll",
       .description = "LDM structure (\"all\": every one)", .column = columns::kStructure.name},
      1, [](const RunSettings& s) { return s.structures; },
      [](RunSettings& s, const Values& v) { s.structures = v; },
      [](const AxisValues& c, bool) {
        const std::string s = value_of(c, "structures");
        return "-" + (s.empty() ? std::string(kNoStructure) : s);
      });
  axes.back().absent_value = kNoStructure;

  add({.key = "views", .label = "N", .flags = "-N,--views", .kind = AxisKind::UInt, .min = 1, .max = 4096,
       .default_value = "32", .ldm_only = true, .unit = "views",
       .description = "number of LDM views N (regions of the hemisphere partition)",
       .column = columns::kNViews.name},
      3, [](const RunSettings& s) { return texts(s.views, [](uint32_t v) { return std::to_string(v); }); },
      [](RunSettings& s, const Values& v) { s.views = parsed<uint32_t>(v, to_u32); },
      [](const AxisValues& c, bool) { return "-n" + value_of(c, "views"); });
  axes.back().absent_value = "0";  // a peer's record has always said N = 0

  add({.key = "r_ldm", .label = "R_LDM", .flags = "-R,--r-ldm", .kind = AxisKind::UInt, .min = 1, .max = 8192,
       .default_value = "128", .ldm_only = true, .unit = "pixels",
       .description = "LDM resolution R_LDM (R x R pixels per view)", .column = columns::kRLdm.name},
      4, [](const RunSettings& s) { return texts(s.resolutions, [](uint32_t v) { return std::to_string(v); }); },
      [](RunSettings& s, const Values& v) { s.resolutions = parsed<uint32_t>(v, to_u32); },
      [](const AxisValues& c, bool) { return "-r" + value_of(c, "r_ldm"); });
  axes.back().absent_value = "0";

  add(ao_axis(AoAxis::DMax), 5,
      [](const RunSettings& s) { return texts(s.d_max, [](float d) { return shortest_text(d, true); }); },
      [](RunSettings& s, const Values& v) {
        s.d_max = parsed<float>(v, [](const std::string& t) { return std::strtof(t.c_str(), nullptr); });
      },
      [](const AxisValues& c, bool) { return d_fragment(value_of(c, "d_max")); });

  add(ao_axis(AoAxis::Visibility), 6,
      [](const RunSettings& s) { return texts(s.visibility, visibility_name); },
      [](RunSettings& s, const Values& v) { s.visibility = parsed<Visibility>(v, parse_visibility_name); },
      [](const AxisValues& c, bool) -> std::string {
        const std::string v = value_of(c, "visibility");
        return v == "attenuated" ? "-att" : v == "unattenuated" ? "-unatt" : "";
      });

  add(ao_axis(AoAxis::NormalOffset), 7,
      [](const RunSettings& s) {
        return s.normal_offset_pixels ? Values{shortest_text(*s.normal_offset_pixels, true)} : Values{};
      },
      [](RunSettings& s, const Values& v) {
        if (v.empty())
          s.normal_offset_pixels.reset();
        else
          s.normal_offset_pixels = std::strtof(v.front().c_str(), nullptr);
      },
      // Named when given: two offsets are two measurements (before issue 18 they shared an id).
      [](const AxisValues& c, bool) {
        const std::string v = value_of(c, "normal_offset");
        return v.empty() ? std::string() : "-off" + v;
      });

  add(ao_axis(AoAxis::Trace), 8, [](const RunSettings& s) { return texts(s.traces, ao_trace_name); },
      [](RunSettings& s, const Values& v) { s.traces = parsed<AoTrace>(v, parse_ao_trace); },
      [](const AxisValues& c, bool) { return "-" + value_of(c, "trace"); });

  add(ao_axis(AoAxis::Estimator), 9,
      [](const RunSettings& s) { return texts(s.estimators, ao_estimator_name); },
      [](RunSettings& s, const Values& v) { s.estimators = parsed<AoEstimatorChoice>(v, parse_ao_estimator); },
      [](const AxisValues& c, bool) {
        const std::string v = value_of(c, "ao_estimator");
        return v == ao_estimator_name(AoEstimatorChoice::Eq13) ? std::string() : "-" + v;
      });

  // Ranks 90 and 95 are the structure's and the pass's parameters (configuration_id).
  add({.key = "sizing", .label = "sizing policy", .flags = "--sizing", .kind = AxisKind::Choice,
       .choices = sizing_policy_names(), .default_value = "previous_frame", .ldm_only = true,
       .description = "how structures learn their sizes: previous_frame (the last frame's counters, rebuild on overflow, timed), census (a timed counting pass every frame), oracle (the untimed census before the run), budget (a fixed memory budget, overflow counted)",
       .column = columns::kSizingPolicy.name},
      100,
      [](const RunSettings& s) { return texts(s.sizing, [](SizingPolicy p) { return std::string(sizing_policy_name(p)); }); },
      [](RunSettings& s, const Values& v) { s.sizing = parsed<SizingPolicy>(v, parse_sizing_policy); },
      // append(), not "-" + ...: GCC 12 sees a false -Wrestrict overlap there once inlined.
      [](const AxisValues& c, bool) { return std::string("-").append(sizing_id_name(parse_sizing_policy(value_of(c, "sizing")))); });
  axes.back().absent_value = kNoStructure;  // a pass that reads no LDM sizes no structure

  add({.key = "sizing_budget_mib", .label = "budget", .flags = "--sizing-budget-mib", .kind = AxisKind::Real,
       .min = 0.001, .max = 1048576, .real_is_double = true,
       .default_note = "none; required by the budget policy", .list = false, .ldm_only = true, .unit = "MiB",
       .description = "memory budget of the budget policy per structure (all its buffers)",
       .column = "sizing_budget_mib"},
      101,
      [](const RunSettings& s) { return s.sizing_budget_mib > 0 ? Values{shortest_text(s.sizing_budget_mib, false)} : Values{}; },
      [](RunSettings& s, const Values& v) { s.sizing_budget_mib = v.empty() ? 0.0 : std::strtod(v.front().c_str(), nullptr); },
      [](const AxisValues& c, bool) -> std::string {
        if (value_of(c, "sizing") != "budget") return "";
        char buffer[32];
        std::snprintf(buffer, sizeof buffer, "%g", std::strtod(value_of(c, "sizing_budget_mib").c_str(), nullptr));
        return buffer;  // follows "-budget"
      });
  axes.back().writes_column = false;  // the policy's sizing_budget_mib

  add({.key = "sizing_initial_per_pixel", .label = "initial guess", .flags = "--sizing-initial-per-pixel",
       .kind = AxisKind::UInt, .min = 1, .max = 4096, .default_value = "1", .list = false, .ldm_only = true,
       .unit = "fragments per LDM pixel", .description = "previous_frame's first guess",
       .column = "sizing_initial"},
      102,
      [](const RunSettings& s) { return Values{std::to_string(s.sizing_initial_per_pixel)}; },
      [](RunSettings& s, const Values& v) { s.sizing_initial_per_pixel = v.empty() ? 1 : to_u32(v.front()); },
      [](const AxisValues& c, bool) -> std::string {
        const std::string v = value_of(c, "sizing_initial_per_pixel");
        return value_of(c, "sizing") == "previous_frame" && !v.empty() && v != "1" ? "-guess" + v : "";
      });
  axes.back().writes_column = false;  // the policy's sizing_initial

  add({.key = "image_size", .label = "image size", .flags = "--image-size", .kind = AxisKind::ImageSize,
       .min = 16, .max = 16384, .default_value = "256x256", .list = false, .unit = "pixels",
       .description = "output image WIDTHxHEIGHT (also --width and --height)",
       .column = columns::kWidth.name + "," + columns::kHeight.name},
      200,
      [](const RunSettings& s) { return Values{std::to_string(s.width) + "x" + std::to_string(s.height)}; },
      [](RunSettings& s, const Values& v) {
        if (v.empty()) return;
        s.width = std::atoi(v.front().c_str());
        s.height = std::atoi(v.front().c_str() + v.front().find('x') + 1);
      },
      [](const AxisValues& c, bool varied) { return varied ? "-img" + value_of(c, "image_size") : std::string(); });
  axes.back().column_rank = 85;  // width and height before the parameters, as records have had them

  add({.key = "frames", .flags = "--frames", .kind = AxisKind::UInt, .min = 1, .max = 100000,
       .default_value = "5", .list = false, .unit = "frames",
       .description = "measured frames per repetition, at least (more until --time-target is met)",
       .column = columns::kFrames.name},
      201, [](const RunSettings& s) { return Values{std::to_string(s.frames)}; },
      [](RunSettings& s, const Values& v) { s.frames = v.empty() ? 5 : int(to_u32(v.front())); },
      // Named with the warm-up when the plan varies either (the warm-up axis sets `varied`
      // here through configuration_id).
      [](const AxisValues& c, bool varied) {
        return varied ? "-f" + value_of(c, "frames") + "w" + value_of(c, "warmup") : std::string();
      });

  add({.key = "warmup", .label = "warm-up frames", .flags = "--warmup", .kind = AxisKind::UInt, .min = 0,
       .max = 100000, .default_value = "2", .list = false, .unit = "frames",
       .description = "warm-up frames judged and discarded before measuring", .column = columns::kWarmup.name},
      202, [](const RunSettings& s) { return Values{std::to_string(s.warmup)}; },
      [](RunSettings& s, const Values& v) { s.warmup = v.empty() ? 2 : int(to_u32(v.front())); }, none);

  (void)none;
  return axes;
}
#pragma GCC diagnostic pop

std::vector<HarnessAxis>& axis_list_storage() {
  static std::vector<HarnessAxis> axes = declare();
  return axes;
}

}  // namespace

const std::vector<HarnessAxis>& harness_axes() { return axis_list_storage(); }

void register_harness_axis(HarnessAxis axis) {
  if (find_harness_axis(axis.spec.key))
    throw std::logic_error("harness axis '" + axis.spec.key + "' is declared twice");
  axis_list_storage().push_back(std::move(axis));
}



const HarnessAxis* find_harness_axis(const std::string& key) {
  for (const auto& a : harness_axes())
    if (a.spec.key == key) return &a;
  return nullptr;
}

std::vector<std::string> axis_list(const RunSettings& settings, const HarnessAxis& axis) {
  if (axis.get) return axis.get(settings);
  const auto it = settings.axis_lists.find(axis.spec.key);
  return it == settings.axis_lists.end() ? std::vector<std::string>() : it->second;
}

void set_axis_list(RunSettings& settings, const HarnessAxis& axis, const std::vector<std::string>& values) {
  if (axis.set)
    axis.set(settings, values);
  else
    settings.axis_lists[axis.spec.key] = values;
}

Configuration configuration_of(const AxisValues& values) {
  Configuration c;
  c.values = values;
  c.scene = value_of(values, "scenes");
  c.pass = value_of(values, "passes");
  c.structure = values.count("structures") ? value_of(values, "structures") : std::string(kNoStructure);
  if (values.count("views")) c.views = to_u32(value_of(values, "views"));
  if (values.count("r_ldm")) c.resolution = to_u32(value_of(values, "r_ldm"));
  if (values.count("image_size")) {  // canonical "WxH" (axis.cpp checked it)
    const std::string size = value_of(values, "image_size");
    c.width = int(to_u32(size.substr(0, size.find('x'))));
    c.height = int(to_u32(size.substr(size.find('x') + 1)));
  }
  if (values.count("d_max")) c.d_max = std::strtof(value_of(values, "d_max").c_str(), nullptr);
  if (values.count("visibility")) c.visibility = parse_visibility_name(value_of(values, "visibility"));
  if (values.count("trace")) c.trace = parse_ao_trace(value_of(values, "trace"));
  if (values.count("ao_estimator")) c.estimator = parse_ao_estimator(value_of(values, "ao_estimator"));
  if (values.count("sizing")) c.sizing.policy = parse_sizing_policy(value_of(values, "sizing"));
  if (values.count("sizing_budget_mib"))
    c.sizing.budget_bytes = uint64_t(std::strtod(value_of(values, "sizing_budget_mib").c_str(), nullptr) *
                                     double(1u << 20));
  if (values.count("sizing_initial_per_pixel"))
    c.sizing.initial_per_pixel = to_u32(value_of(values, "sizing_initial_per_pixel"));
  // Parameters: "OWNER:KEY" of the structure's or the pass's own.
  for (const auto& [key, value] : values) {
    const auto colon = key.find(':');
    if (colon == std::string::npos) continue;
    const std::string owner = key.substr(0, colon), name = key.substr(colon + 1);
    if (owner == c.structure) c.params[name] = value;
    if (owner == c.pass) c.pass_params[name] = value;
    // A pass without a structure: its own parameters stand where a structure's would (the
    // record's structure_params), as they always have.
    if (owner == c.pass && c.structure == kNoStructure) c.params[name] = value;
  }
  // The AO settings reach the pass as its parameters (harness/passes/ao_parameters.h): those
  // it declares, when they differ from their defaults.
  if (!c.pass.empty()) {
    const std::vector<AxisSpec> declared = pass_parameters(c.pass);
    for (const HarnessAxis& axis : harness_axes()) {
      const AxisSpec& spec = axis.spec;
      if (spec.pass_parameter.empty() || !find_axis(declared, spec.pass_parameter)) continue;
      const std::string v = value_of(values, spec.key);
      if (!v.empty() && v != spec.default_value) c.pass_params[spec.pass_parameter] = v;
    }
  }
  return c;
}

namespace {

constexpr int kParametersRank = 90;  // the structure's parameters, in the id and the columns

int column_rank(const HarnessAxis& axis) { return axis.column_rank.value_or(axis.id_rank); }

std::vector<std::string> split_columns(const std::string& columns) { return split_nonempty(columns, ","); }

void put_axis_value(Record& r, const AxisSpec& spec, const std::string& text) {
  const std::vector<std::string> columns = split_columns(spec.column);
  if (spec.kind == AxisKind::ImageSize) {
    if (columns.size() != 2)
      throw std::logic_error("axis '" + spec.key + "': an image size needs two columns (width,height)");
    const auto x = text.find('x');
    r.set(columns[0], std::atoi(text.c_str()));
    r.set(columns[1], x == std::string::npos ? 0 : std::atoi(text.c_str() + x + 1));
    return;
  }
  if (columns.size() != 1)
    throw std::logic_error("axis '" + spec.key + "' writes one column, not '" + spec.column + "'");
  if (spec.kind == AxisKind::UInt)
    r.set(columns[0], int64_t(std::strtoll(text.c_str(), nullptr, 10)));
  else if (spec.kind == AxisKind::Real)
    r.set(columns[0], std::strtod(text.c_str(), nullptr));
  else
    r.set(columns[0], text);
}

}  // namespace

void write_axis_columns(Record& r, const Configuration& config, AxisColumns which) {
  std::vector<const HarnessAxis*> axes;
  for (const HarnessAxis& axis : harness_axes())
    if (axis.writes_column && !axis.spec.column.empty() && (which == AxisColumns::All || axis.spec.list))
      axes.push_back(&axis);
  std::stable_sort(axes.begin(), axes.end(),
                   [](const HarnessAxis* a, const HarnessAxis* b) { return column_rank(*a) < column_rank(*b); });
  bool parameters_written = false;
  const auto write_parameters = [&] {
    std::string params;
    for (const auto& [key, value] : config.params) params += (params.empty() ? "" : ";") + key + "=" + value;
    r.set("structure_params", params);
    parameters_written = true;
  };
  for (const HarnessAxis* axis : axes) {
    if (!parameters_written && column_rank(*axis) >= kParametersRank) write_parameters();
    const auto it = config.values.find(axis->spec.key);
    if (it != config.values.end())
      put_axis_value(r, axis->spec, it->second);
    else if (!axis->absent_value.empty())
      put_axis_value(r, axis->spec, axis->absent_value);
    else
      for (const auto& column : split_columns(axis->spec.column)) r.put(column, std::monostate{});
  }
  if (!parameters_written) write_parameters();
}

std::vector<std::string> axis_column_names() {
  std::vector<std::string> names;
  for (const HarnessAxis& axis : harness_axes())
    if (axis.writes_column)
      for (const auto& column : split_columns(axis.spec.column)) names.push_back(column);
  names.push_back("structure_params");
  return names;
}

std::string configuration_id(const AxisValues& values, const std::set<std::string>& varied) {
  // The parameters' fragments stand between the AO axes and the sizing policy.
  std::vector<std::pair<int, std::string>> parts;
  for (const HarnessAxis& axis : harness_axes()) {
    if (!axis.id_fragment) continue;
    const std::string& key = axis.spec.key;
    // A configuration holds only the axes that apply to it (a peer has no N); the structure
    // names itself "none" then.
    if (!values.count(key) && key != "structures") continue;
    const bool is_varied = varied.count(key) || (key == "frames" && varied.count("warmup"));
    parts.emplace_back(axis.id_rank, axis.id_fragment(values, is_varied));
  }
  const std::string structure = value_of(values, "structures");
  const std::string pass = value_of(values, "passes");
  for (const auto& [key, value] : values) {
    const auto colon = key.find(':');
    if (colon == std::string::npos) continue;
    const std::string owner = key.substr(0, colon);
    const int rank = owner == structure ? kParametersRank : owner == pass ? 95 : -1;
    if (rank >= 0) parts.emplace_back(rank, "-" + key.substr(colon + 1) + "=" + value);
  }
  std::stable_sort(parts.begin(), parts.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  std::string id;
  for (size_t i = 0; i < parts.size(); ++i) {
    // The budget's fragment continues the policy's ("-budget" + "8").
    id += parts[i].second;
  }
  for (char& ch : id)
    if (!(std::isalnum(static_cast<unsigned char>(ch)) || ch == '-' || ch == '_' || ch == '.' || ch == '='))
      ch = '_';
  return id;
}

}  // namespace ldm
