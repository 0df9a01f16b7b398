#pragma once
// One axis of a sweep, declared once by its owner (in the manner of nvbench's axes): the
// harness declares the axes every configuration has (scene, N, R_LDM, image size, sizing
// policy...: harness/settings/harness_axes.cpp), a structure or a pass declares its own
// parameters beside the code that reads them (ldm_impls/*, harness/passes/*). Everything
// that names, parses, checks, lists or serialises an axis is derived from its AxisSpec:
// the command line's options, sweep-file validation, ldmbench_gbench's flags, the viewer's
// controls, configuration ids, the re-serialised command line, the records' identity
// columns and `ldmbench axes` (harness/settings/axis_registry.h).
//
// Values travel as canonical text: what `--param ppfla:k=4` or `-N 32` carries, checked and
// normalised by canonical_axis_value() (an integer without leading zeros, a real as the
// shortest text of the float or double the run uses, a choice as its name).
#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace ldm {

enum class AxisKind {
  Text,       // any non-empty text (a scene name or file)
  Choice,     // one of a list of names
  UInt,       // an integer in [min, max]
  Real,       // a real in [min, max], as the 32-bit float the GPU uses (or a double)
  Bool,       // true or false (also 1/0, on/off, yes/no on input)
  ImageSize,  // WIDTHxHEIGHT, or one integer for a square image, each side in [min, max]
};
const char* axis_kind_name(AxisKind kind);  // text, choice, uint, real, bool, image_size

struct AxisSpec {
  // The name in sweep files and records' axis lists ("views"); for an owner's parameter
  // the key of --param OWNER:KEY ("k"), known qualified as "ppfla:k".
  std::string key;
  // "harness", or the structure or pass whose parameter this is.
  std::string owner = "harness";
  // How messages and tables call it ("N", "R_LDM"); the key when empty.
  std::string label;
  // Command-line names of a harness axis, CLI11 style: "-N,--views". Empty for parameters
  // (set through --param OWNER:KEY=VALUE) and for axes only sweep files vary.
  std::string flags;
  AxisKind kind = AxisKind::Text;
  double min = 0, max = 0;  // UInt, Real, ImageSize (inclusive)
  bool real_is_double = false;  // Real: checked as a double rather than a 32-bit float
  std::vector<std::string> choices;                           // Choice
  std::function<std::vector<std::string>()> dynamic_choices;  // Choice known at run time
  // The value when none is given, canonical; empty when there is none (the scene's own, the
  // structure's automatic choice): default_note says what happens then.
  std::string default_value;
  std::string default_note;
  // Whether the command line takes a comma list (a sweep axis) or one value.
  bool list = true;
  // Whether the value changes what is measured. Identity axes are part of the
  // configuration's identity (its id, the resume identity); the others (notes) are not.
  bool identity = true;
  // Whether only configurations with an LDM structure have this axis (N, R_LDM, trace...).
  bool ldm_only = false;
  std::string unit;
  std::string description;
  // The record column(s) holding the axis's value, comma-separated ("width,height"; "" when
  // it has none of its own; a structure's parameters share structure_params).
  std::string column;
  // Set when the value reaches the pass as a parameter of this name (d_max, trace...): the
  // pass reads it, but it is set through this axis only, never as --param PASS:NAME.
  std::string pass_parameter;

  std::string qualified() const { return owner == "harness" ? key : owner + ":" + key; }
  std::string display_name() const { return label.empty() ? key : label; }
};

// The names a Choice axis accepts (static or dynamic).
std::vector<std::string> axis_choices(const AxisSpec& spec);

// A Real axis's value as the run uses it (a 32-bit float unless real_is_double), and why it
// is refused ("" when it is not): "3e38 reads as 3e+38 in a 32-bit float; it must lie in
// [1e-30, 1e+30]". `text` is the value as given ("" prints `value`). One check for the
// command line, sweep files and scene files (scene_loader.cpp reads ao.d_max through it).
double axis_real_used(const AxisSpec& spec, double value);
std::string axis_real_problem(const AxisSpec& spec, double value, const std::string& text = "");

// Checks `text` against the axis and returns it in canonical form. Throws UserError
// "<where>: <what is wrong>" naming the axis, its range or its choices.
std::string canonical_axis_value(const AxisSpec& spec, const std::string& text,
                                 const std::string& where);

// The value of a JSON item (a sweep file's) as the text --param would carry: strings as
// they are, integers in decimal, reals as the shortest round-tripping text, booleans as
// true/false. Throws UserError for anything else (objects, arrays, null, NaN).
std::string axis_text_of_json(const nlohmann::json& value, const std::string& where);

// The canonical text as the JSON a sweep file would hold (numbers as numbers).
nlohmann::json axis_json_of_text(const AxisSpec& spec, const std::string& canonical);

// The shortest %g text that reads back as `value` (as a float when `as_float`): how
// canonical values, ranges and messages print numbers (2147483647 exactly, 0.1 not 0.100000001).
std::string shortest_text(double value, bool as_float);
// "[min, max]" of a UInt, Real or ImageSize axis: integral bounds in full, others in
// shortest_text.
std::string axis_range_text(const AxisSpec& spec);

// The declaration as JSON (`ldmbench axes --json`).
nlohmann::json axis_spec_json(const AxisSpec& spec);

// A structure's or pass's parameter with the fields most of them set (the rest, such as
// default_note, label or real_is_double, are set on the result): a UInt or Real in
// [min, max], a Choice among `choices`. `column` is the record column holding it, if any.
AxisSpec numeric_parameter(std::string key, AxisKind kind, double min, double max,
                           std::string default_value, std::string unit, std::string description,
                           std::string column = "");
AxisSpec choice_parameter(std::string key, std::vector<std::string> choices,
                          std::string default_value, std::string description,
                          std::string column = "");

// The spec of `key` in `specs`, or null.
const AxisSpec* find_axis(const std::vector<AxisSpec>& specs, const std::string& key);

// One configuration's value of every axis that applies to it, canonical: harness axes by key
// ("views"), parameters qualified by their owner ("ppfla:k"). The one carrier of a
// configuration's values from its declaration to its consumers: measure() hands it to every
// pass (PassInputs::axes), so that an axis reaches the code that reads it through its
// declaration and that code alone.
using AxisValues = std::map<std::string, std::string>;

// The value of axis `key` in `values`, read as a number or as text (nullopt: the
// configuration has no such axis). The values are canonical, so a number that does not
// parse is a harness bug: std::logic_error naming the key.
std::optional<double> axis_real(const AxisValues& values, const std::string& key);
std::optional<uint64_t> axis_uint(const AxisValues& values, const std::string& key);
std::optional<std::string> axis_text(const AxisValues& values, const std::string& key);

// "--name" of a CLI11 flags string ("-N,--views" -> "--views"; "-R" -> "-R").
std::string long_flag(const std::string& flags);

}  // namespace ldm
