#include "harness/run/run_summary.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>

#include "harness/measuring/timing_columns.h"
#include "harness/records/columns.h"
#include "harness/util/text.h"

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

std::string text(const Record& r, const std::string& key) {
  const RecordValue* v = r.get(key);
  const std::string* s = v ? std::get_if<std::string>(v) : nullptr;
  return s ? *s : "-";
}

bool is_false(const Record& r, const std::string& key) {
  const RecordValue* v = r.get(key);
  const bool* b = v ? std::get_if<bool>(v) : nullptr;
  return b && !*b;
}

// The notes of status_detail ("; "-separated).
std::vector<std::string> detail_notes(const Record& r) {
  const std::string detail = text(r, "status_detail");
  if (detail == "-") return {};
  return split_nonempty(detail, "; ");
}

// A flag: its letter and meaning, whether the record's columns raise it, and which notes of
// status_detail it explains (so that they are not counted again under W).
struct FlagRule {
  StatusFlag flag;
  std::function<bool(const Record&)> raised;
  std::string note_text;  // a note containing this is the flag's
};

const std::vector<FlagRule>& flag_rules() {
  static const std::vector<FlagRule> rules = {
      {{'D', "degenerate (measures nothing; never ranked)"},
       [](const Record& r) { const std::string d = text(r, "degenerate"); return d != "-" && !d.empty(); },
       "degenerate: "},
      {{'T', "time target missed"},
       [](const Record& r) { return is_false(r, "time_target_met"); }, "time target missed"},
      {{'N', "reference noise target missed"},
       [](const Record& r) { return is_false(r, "ref_noise_target_met") || is_false(r, "multi_ref_noise_target_met"); },
       "reference noise target not met"},
      {{'R', "reference ray offset large (reference may be biased)"},
       [](const Record& r) { return is_false(r, "ref_ray_offset_ok") || is_false(r, "multi_ref_ray_offset_ok"); },
       "reference ray offset"},
      {{'X', "driver defects"},
       [](const Record& r) {
         const std::string d = text(r, "driver_defects");
         return d != "-" && !d.empty() && d != "none";
       },
       "\x01"},  // driver_defects is its own column, never a note
  };
  return rules;
}

}  // namespace

std::vector<StatusFlag> status_flags(const Record& record) {
  std::vector<StatusFlag> flags;
  std::vector<std::string> unexplained = detail_notes(record);
  for (const FlagRule& rule : flag_rules()) {
    bool explains = false;
    for (auto it = unexplained.begin(); it != unexplained.end();)
      if (it->find(rule.note_text) != std::string::npos) {
        it = unexplained.erase(it);
        explains = true;
      } else {
        ++it;
      }
    if (rule.raised(record) || explains) flags.push_back(rule.flag);
  }
  // A record that is not ok has its status say so, and status_detail why; an ok one carries
  // its other notes here.
  if (text(record, "status") == "ok" && !unexplained.empty())
    flags.push_back({'W', "another warning (status_detail)"});
  return flags;
}

std::string status_cell(const Record& record) {
  std::string letters;
  for (const StatusFlag& f : status_flags(record)) letters += f.letter;
  return text(record, "status") + (letters.empty() ? "" : " [" + letters + "]");
}

namespace {

// Characters a terminal shows (UTF-8 continuation bytes take no column).
size_t display_width(const std::string& s) {
  size_t n = 0;
  for (unsigned char c : s) n += (c & 0xC0) != 0x80;
  return n;
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
  const std::vector<std::string> columns = {"config_id", "status", "build_ms_median", "pass_ms_median",
                                            "frame_ms_median", "bytes_allocated", "bytes_used", "mse",
                                            "mssim", "mse_covered", "mssim_covered", "mse_over_noise"};
  std::vector<std::string> header;
  for (const auto& c : columns) header.push_back(column_heading(c));
  std::vector<std::vector<std::string>> rows = {header};
  std::vector<StatusFlag> shown_flags;
  const size_t shown = std::min(records.size(), max_rows);
  for (size_t i = 0; i < shown; ++i) {
    const Record& r = records[i];
    std::vector<std::string> row = {text(r, "config_id"), status_cell(r)};
    for (size_t c = 2; c < columns.size(); ++c) {
      const std::string& column = columns[c];
      if (column.ends_with("_ms_median"))
        row.push_back(time_cell(r, column.substr(0, column.size() - std::string("_ms_median").size())));
      else
        row.push_back(cell(r, column, column_label(column).scale));
    }
    rows.push_back(std::move(row));
    for (const StatusFlag& f : status_flags(r))
      if (std::none_of(shown_flags.begin(), shown_flags.end(), [&](const StatusFlag& s) { return s.letter == f.letter; }))
        shown_flags.push_back(f);
  }
  std::vector<size_t> width(header.size(), 0);
  for (const auto& row : rows)
    for (size_t c = 0; c < row.size(); ++c) width[c] = std::max(width[c], display_width(row[c]));
  std::string out;
  for (const auto& row : rows) {
    std::string line;
    for (size_t c = 0; c < row.size(); ++c) {
      const size_t pad = width[c] - display_width(row[c]);
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
  out += "↓ lower is better, ↑ higher is better; MSE covered, MSSIM covered: over the pixels where "
         "the camera sees a surface";
  std::sort(shown_flags.begin(), shown_flags.end(), [](const StatusFlag& a, const StatusFlag& b) {
    return std::string("DTNRXW").find(a.letter) < std::string("DTNRXW").find(b.letter);
  });
  if (!shown_flags.empty()) {
    out += "\nstatus flags:";
    for (size_t i = 0; i < shown_flags.size(); ++i)
      out += std::string(i ? "," : "") + " " + shown_flags[i].letter + " " + shown_flags[i].meaning;
    out += " (status_detail in records.csv says more)";
  }
  return out + "\n";
}

}  // namespace ldm
