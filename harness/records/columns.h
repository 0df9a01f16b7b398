#pragma once
// The record schema's parts: every column has a unit and a one-line description, declared by
// the code that writes it. The harness's own columns (identity, device, scene, census, build,
// time, memory, accuracy, images, profile) are here; each pass declares the columns it writes
// (Pass columns(), beside its describe() and results()); harness/settings/record_schema.h puts them
// together for `ldmbench columns`, the generated records table (docs/reference/records.md)
// and the tests that check that every column of a real run is described.
//
// A name may hold one placeholder in angle brackets standing for a non-empty word:
// "counter_<name>" describes counter_max_age_used, counter_lists_sorted_in_place, ...
#include <string>
#include <utility>
#include <vector>

namespace ldm {

// What a column holds: a number, text, a flag (true/false), or (a pattern's or a pass's
// column not yet typed) any of them.
enum class ColumnKind { Number, Text, Flag, Mixed };
// Whether two runs of the same configuration on the same build can differ in the column
// (measured time, the machine's state, which host or job measured): what compare, same_records
// and the Python readers leave out when they compare runs.
enum class VariesBetweenRuns { No, Yes };
// Which way is better: what the console's table and the report show beside a label (↓ ↑).
enum class Better { Lower = -1, Neither = 0, Higher = 1 };
// Whether a value is summed in a fixed order, or in the order that arrival decides where a
// pass blends or adds in that order (ColumnSpec::summed_in_arrival_order).
enum class Summation { FixedOrder, ArrivalOrder };

// One column of the record schema, declared once by the code that writes it (the harness's
// own: harness/records/harness_columns.h; a pass's: its columns()). Record::set takes the
// declaration (or a declared name).
struct ColumnSpec {
  std::string group;  // identity, device, scene, pass, census, build, time, memory, accuracy, images
  std::string name;   // exact, or with one <placeholder>
  std::string unit;   // empty for text, flags and plain ratios
  std::string description;
  ColumnKind kind = ColumnKind::Mixed;
  bool varies_between_runs = false;
  // Whether the same configuration on the same build and device always gives the same value
  // (the work counters of a structure): every column that does not vary between runs.
  bool deterministic = true;
  Better better = Better::Neither;
  // Whether the value is summed in an order that arrival decides where a pass blends or adds
  // in that order (the indirect pass's splats and flux audits): two runs then agree within
  // the record's image_order_tolerance (relative), not exactly. Exact for every record whose
  // pass declares no such tolerance (AO and the peers).
  bool summed_in_arrival_order = false;

  ColumnSpec() = default;
  ColumnSpec(std::string group_, std::string name_, std::string unit_, std::string description_,
             ColumnKind kind_ = ColumnKind::Mixed, VariesBetweenRuns varies = VariesBetweenRuns::No,
             Better better_ = Better::Neither, Summation summation = Summation::FixedOrder)
      : group(std::move(group_)),
        name(std::move(name_)),
        unit(std::move(unit_)),
        description(std::move(description_)),
        kind(kind_),
        varies_between_runs(varies == VariesBetweenRuns::Yes),
        deterministic(varies == VariesBetweenRuns::No),
        better(better_),
        summed_in_arrival_order(summation == Summation::ArrivalOrder) {}
};
using Column = ColumnSpec;
const char* column_kind_name(ColumnKind kind);  // number, text, flag, mixed

const std::vector<ColumnSpec>& harness_record_columns();

// The short names the console's end-of-run table, the report (scripts/report/ldmreport/
// labels.json, generated from `ldmbench columns --labels`) and the docs give the headline
// columns, and which way is better: one vocabulary. `scale` turns the column's unit into the
// label's (bytes -> MiB).
struct ColumnLabel {
  std::string column, label;
  int better = 0;  // -1 lower is better, +1 higher is better, 0 neither
  double scale = 1.0;
};
const std::vector<ColumnLabel>& column_labels();
// The label of `column` ("MSE" for mse), the column's own name when it has none.
const ColumnLabel& column_label(const std::string& column);
// The label with its direction: "MSE ↓", "MSSIM ↑", "configuration".
std::string column_heading(const std::string& column);
// The labels as JSON ({"columns": [{"column", "label", "better", "scale"}...], "arrows"}).
std::string column_labels_json();
// The spec in `columns` describing `column` (exact names first, then patterns), or null.
const ColumnSpec* find_column_in(const std::vector<ColumnSpec>& columns, const std::string& column);
// The records table (Markdown) and the plain listing of `ldmbench columns`.
std::string columns_markdown(const std::vector<ColumnSpec>& columns);
std::string columns_text(const std::vector<ColumnSpec>& columns);
// Every column with its unit, description, kind and flags, as JSON ({"columns": [{"group",
// "name", "unit", "description", "kind", "varies_between_runs", "deterministic", "better"}...]};
// better: "lower", "higher" or "neither"): what the Python readers take the run-varying
// columns from.
std::string columns_json(const std::vector<ColumnSpec>& columns);

}  // namespace ldm
