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
// The spec in `columns` describing `column` (exact names first, then patterns), or null.
const ColumnSpec* find_column_in(const std::vector<ColumnSpec>& columns, const std::string& column);
// The records table (Markdown) and the plain listing of `ldmbench columns`.
std::string columns_markdown(const std::vector<ColumnSpec>& columns);
std::string columns_text(const std::vector<ColumnSpec>& columns);

}  // namespace ldm
