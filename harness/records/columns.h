#pragma once
// The record schema: every column `ldmbench run` writes, with its unit and a one-line
// description, in one place. `ldmbench columns` prints it; the records table of
// docs/reference/records.md is generated from it (`ldmbench columns --markdown`) and a test checks that they agree and
// that every column of a real run is described here.
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

const std::vector<ColumnSpec>& record_columns();
// The spec describing `column` (exact names first, then patterns), or null.
const ColumnSpec* find_column(const std::string& column);
// The records table of docs/reference/records.md (Markdown) and the plain listing of `ldmbench columns`.
std::string columns_markdown();
std::string columns_text();

}  // namespace ldm
