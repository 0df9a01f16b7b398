#pragma once
// The record schema's parts: every column has a unit and a one-line description, declared by
// the code that writes it. The harness's own columns (identity, device, scene, census, build,
// time, memory, accuracy, images, profile) are here; each pass declares the columns it writes
// (Pass columns(), beside its describe() and results()); harness/app/record_schema.h puts them
// together for `ldmbench columns`, the generated records table (docs/reference/records.md)
// and the tests that check that every column of a real run is described.
//
// A name may hold one placeholder in angle brackets standing for a non-empty word:
// "counter_<name>" describes counter_max_age_used, counter_lists_sorted_in_place, ...
#include <string>
#include <vector>

namespace ldm {

struct ColumnSpec {
  std::string group;  // identity, device, scene, pass, census, build, time, memory, accuracy, images
  std::string name;   // exact, or with one <placeholder>
  std::string unit;   // empty for text, flags and plain ratios
  std::string description;
};

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

}  // namespace ldm
