#pragma once
// The axes the harness owns (scene, structure, pass, N, R_LDM, the AO settings, the sizing
// policy, image size, frames), each declared once in harness_axes.cpp with its binding to
// RunSettings and its part of the configuration id. Structures and passes declare their own
// parameters (structure_parameters(), pass_parameters()); harness/settings/axis_registry.h puts
// both together for everything that is derived from them.
#include <functional>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "harness/settings/run_settings.h"
#include "harness/axes/axis.h"
#include "harness/records/record.h"

namespace ldm {

struct HarnessAxis {
  AxisSpec spec;
  // The run's values of the axis, canonical (empty: none given, the default applies), and
  // how a list of canonical values is stored. Without a binding the values live in
  // RunSettings::axis_lists under the axis's key (an axis that only passes read).
  std::function<std::vector<std::string>(const RunSettings&)> get;
  std::function<void(RunSettings&, const std::vector<std::string>&)> set;
  // The axis's part of the configuration id, from the configuration's values; `varied`
  // tells whether the plan gives this axis more than one value (image size and frames are
  // named only then). Null: not part of the id.
  std::function<std::string(const AxisValues& values, bool varied)> id_fragment;
  // Where the fragment stands in the id (smaller first).
  int id_rank = 0;
  // Whether the axis writes its record column (spec.column) itself, through
  // write_axis_columns; false where the consumer writes it (the AO settings: the pass's
  // describe(); the sizing budget and first guess: the sizing policy's sizing_ columns).
  bool writes_column = true;
  // The column's value in a configuration the axis does not apply to (a peer has no N: 0, no
  // structure: none); empty: the column is left blank there.
  std::string absent_value;
  // Where its column stands among the identity columns (smaller first); unset: id_rank. The
  // structure's and pass's parameters (structure_params) stand at 90, as in the id.
  std::optional<int> column_rank;
};

// Every harness axis, in canonical order (sweep files list them so; the product runs the
// first slowest).
const std::vector<HarnessAxis>& harness_axes();
// Adds an axis after the built-in ones (a test's, or an extension's), before anything derives
// from the list (options, plans). Without get/set its values live in RunSettings::axis_lists,
// and its consumer reads Configuration::values; the axis is then an option of `ldmbench run`
// and ldmbench_gbench, a sweep-file key, part of the id and of `ldmbench axes`.
void register_harness_axis(HarnessAxis axis);
const HarnessAxis* find_harness_axis(const std::string& key);

// The run's values of an axis (its binding, else RunSettings::axis_lists), and storing them.
std::vector<std::string> axis_list(const RunSettings& settings, const HarnessAxis& axis);
void set_axis_list(RunSettings& settings, const HarnessAxis& axis, const std::vector<std::string>& values);

// The typed configuration of one combination of values, its id not yet assigned.
Configuration configuration_of(const AxisValues& values);

// Which axes' columns write_axis_columns writes: every one, or only those a sweep lists values
// of (spec.list; the memory plan's, which leaves out the run-wide image size and frames).
enum class AxisColumns { All, Listed };

// The configuration's identity columns, written by looping over the harness axes: each axis
// that writes its column (writes_column) puts its value under spec.column, typed by its kind
// (UInt: an integer, Real: a number, ImageSize: width and height, else text), in column_rank
// order, with the parameters' column structure_params (key=value;...) at rank 90. What a
// measured record and the memory plan identify a configuration by; an axis declared in one
// place reaches the record here.
void write_axis_columns(Record& record, const Configuration& config, AxisColumns which = AxisColumns::All);
// The record columns of the harness axes that write their own (for the schema: an axis
// declared outside the harness's own columns, a test's, still names a declared column).
std::vector<std::string> axis_column_names();

// The configuration id from its values: every harness axis's fragment in id_rank order, then
// the parameters (structure's, then pass's) as -KEY=VALUE, then the characters a file name
// cannot hold replaced by '_'. `varied` lists the axes the plan varies.
std::string configuration_id(const AxisValues& values, const std::set<std::string>& varied);

}  // namespace ldm
