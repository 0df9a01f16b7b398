#pragma once
// The table `ldmbench run` and `ldmbench sweep` print at the end: one aligned row per
// configuration with what a reader looks at first (status, build and pass time, memory,
// error). Times are medians to the digits their 95% interval supports, with its relative
// half-width ("8.97 ±9.3%"); other numbers to 4 significant digits. The records keep
// every digit.
#include <cstddef>
#include <string>
#include <vector>

#include "harness/records/record.h"

namespace ldm {

inline constexpr size_t kSummaryTableRows = 60;

// Columns, headed by the schema's labels with which way is better (column_heading,
// harness/records/columns.h): configuration, status (with its flags), build ms, pass ms (the
// pass's own sub-passes, summed per frame), frame ms, MiB allocated, MiB used, MSE, MSSIM,
// MSE covered, MSSIM covered, MSE / ref noise; "-" where a record has no such value. At most
// `max_rows` rows (then a line saying how many more records.csv holds), then the legend:
// the arrows and each flag shown. Empty for no records.
std::string summary_table(const std::vector<Record>& records, size_t max_rows);

// What a record carries beyond its status, one letter each: degenerate (D), time target
// missed (T), reference noise target missed (N), reference ray offset large (R), driver
// defects (X), and W for any other note of status_detail (a pass's or the scene's warning,
// a precision flag, ...) an ok record carries. Every flag is read from the record's own
// columns; W makes sure that no note of status_detail goes unshown.
struct StatusFlag {
  char letter;
  std::string meaning;
};
std::vector<StatusFlag> status_flags(const Record& record);
// The status column's cell: "ok", "ok [DT]", "lossy [N]".
std::string status_cell(const Record& record);

// A number to 4 significant digits ("24.99757" -> "25", "47.258949" -> "47.26").
std::string four_digits(double value);

}  // namespace ldm
