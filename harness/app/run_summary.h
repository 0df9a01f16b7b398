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

// Columns: configuration, status, build ms, pass ms (the pass's own sub-passes, summed per
// frame), frame ms, MiB allocated, MiB used, MSE, MSSIM, x noise (mse_over_noise); "-"
// where a record has no such value. At most `max_rows` rows (then a line saying how many
// more records.csv holds); empty for no records.
std::string summary_table(const std::vector<Record>& records, size_t max_rows);

// A number to 4 significant digits ("24.99757" -> "25", "47.258949" -> "47.26").
std::string four_digits(double value);

}  // namespace ldm
