#include "harness/app/run_summary.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "harness/app/timing_columns.h"

namespace ldm {
namespace {

const double* number(const Record& r, const std::string& key, double* scratch) {
  const RecordValue* v = r.get(key);
  if (!v) return nullptr;
  if (const double* d = std::get_if<double>(v)) return d;
  if (const int64_t* i = std::get_if<int64_t>(v)) {
    *scratch = double(*i);
    return scratch;
  }
  return nullptr;
}

std::string cell(const Record& r, const std::string& key, double scale = 1.0) {
  double scratch = 0;
  const double* v = number(r, key, &scratch);
  return v ? four_digits(*v * scale) : "-";
}

std::string text(const Record& r, const std::string& key) {
  const RecordValue* v = r.get(key);
  const std::string* s = v ? std::get_if<std::string>(v) : nullptr;
  return s ? *s : "-";
}

// A sum's median with its interval ("8.97 ±9.3%"), "-" when not timed.
std::string time_cell(const Record& r, const std::string& subpass) {
  double a = 0, b = 0, c = 0;
  const double* median = number(r, subpass + "_ms_median", &a);
  if (!median) return "-";
  const double* low = number(r, subpass + "_ms_ci_low", &b);
  const double* high = number(r, subpass + "_ms_ci_high", &c);
  if (!low || !high) return four_digits(*median);
  return format_time_with_interval(*median, *low, *high);
}

}  // namespace

std::string four_digits(double value) {
  if (std::isnan(value)) return "nan";
  if (std::isinf(value)) return value > 0 ? "inf" : "-inf";
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.4g", value);
  return buffer;
}

std::string summary_table(const std::vector<Record>& records, size_t max_rows) {
  if (records.empty()) return "";
  const std::vector<std::string> header = {"configuration", "status", "build ms", "pass ms",
                                           "frame ms",      "MiB alloc", "MiB used", "MSE",
                                           "MSSIM",         "x noise"};
  constexpr double kMiB = 1.0 / (1024.0 * 1024.0);
  std::vector<std::vector<std::string>> rows = {header};
  const size_t shown = std::min(records.size(), max_rows);
  for (size_t i = 0; i < shown; ++i) {
    const Record& r = records[i];
    rows.push_back({text(r, "config_id"), text(r, "status"), time_cell(r, "build"), time_cell(r, "pass"),
                    time_cell(r, "frame"), cell(r, "bytes_allocated", kMiB),
                    cell(r, "bytes_used", kMiB), cell(r, "mse"), cell(r, "mssim"),
                    cell(r, "mse_over_noise")});
  }
  std::vector<size_t> width(header.size(), 0);
  for (const auto& row : rows)
    for (size_t c = 0; c < row.size(); ++c) width[c] = std::max(width[c], row[c].size());
  std::string out;
  for (const auto& row : rows) {
    std::string line;
    for (size_t c = 0; c < row.size(); ++c) {
      const size_t pad = width[c] - row[c].size();
      // Names left-aligned, numbers right-aligned (their digits line up).
      if (c < 2)
        line += row[c] + std::string(pad, ' ');
      else
        line += std::string(pad, ' ') + row[c];
      if (c + 1 < row.size()) line += "  ";
    }
    while (!line.empty() && line.back() == ' ') line.pop_back();
    out += line + "\n";
  }
  if (shown < records.size())
    out += "... " + std::to_string(records.size() - shown) + " more configuration(s) in records.csv\n";
  return out;
}

}  // namespace ldm
