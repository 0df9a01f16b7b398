// The end-of-run table (harness/run/run_summary.h) and the sweep's progress bar text.
#include <gtest/gtest.h>

#include <sstream>

#include "harness/run/run_summary.h"
#include "harness/run/sweep_progress.h"
#include "support/subpass_time.h"

namespace ldm {
namespace {

Record measured(const std::string& id, double build_ms) {
  Record r;
  r.set("config_id", id);
  r.set("status", "ok");
  r.set("pass", "ao");
  r.set("build_ms_median", build_ms);
  r.set("gbuffer_ms_median", 1.25);
  r.set("ao_ms_median", 47.258949);
  r.set("pass_ms_median", 48.51);
  test::set_subpass_time(r, "frame", 73.4, 72.0, 75.0);
  r.set("bytes_allocated", int64_t(3) << 20);
  r.set("bytes_used", int64_t(1) << 19);
  r.set("mse", 0.0012345678);
  r.set("mssim", 0.987654);
  r.set("mse_over_noise", 123.456);
  return r;
}

TEST(RunSummary, FourSignificantDigits) {
  EXPECT_EQ(four_digits(24.99757), "25");
  EXPECT_EQ(four_digits(47.258949), "47.26");
  EXPECT_EQ(four_digits(0.0012345678), "0.001235");
  EXPECT_EQ(four_digits(123456.0), "1.235e+05");
}

TEST(RunSummary, AlignedRowsWithTheColumnsAReaderWants) {
  Record failed;
  failed.set("config_id", "a-much-longer-configuration-id");
  failed.set("status", "failed");
  failed.set("pass", "ao");
  const std::string table = summary_table({measured("short", 24.99757), failed}, 10);
  std::istringstream lines(table);
  std::string header, first, second;
  std::getline(lines, header);
  std::getline(lines, first);
  std::getline(lines, second);
  EXPECT_EQ(header.rfind("configuration", 0), 0u) << table;
  // The schema's labels, each with which way is better.
  for (const char* column : {"status", "build ms ↓", "pass ms ↓", "frame ms ↓", "MiB allocated ↓",
                             "MiB used ↓", "MSE ↓", "MSSIM ↑", "MSE covered ↓", "MSSIM covered ↑",
                             "MSE / ref noise ↓"})
    EXPECT_NE(header.find(column), std::string::npos) << column;
  EXPECT_NE(table.find("↓ lower is better, ↑ higher is better"), std::string::npos) << table;
  // A time with its interval to the digits it supports and its relative half-width (frame:
  // 73.4 in [72, 75] is "73 ±2.2%"), one without to 4 digits; MiB from bytes; 4 digits else.
  for (const char* cell : {" 25 ", " 48.51 ", " 73 ±2.2% ", " 3 ", " 0.5 ", " 0.001235 ", " 0.9877 ", " 123.5"})
    EXPECT_NE((first + " ").find(cell), std::string::npos) << cell << "\n" << table;
  EXPECT_NE(second.find("failed"), std::string::npos);
  EXPECT_NE(second.find(" - "), std::string::npos) << table;  // no value, no number
  // Columns line up: the status column starts at the same offset in every row.
  EXPECT_EQ(first.find("ok"), header.find("status"));
  EXPECT_EQ(second.find("failed"), header.find("status"));
  // Numbers are right-aligned: the rows end at the same column as the header (in columns a
  // terminal shows: the arrows and ± take one each, in more than one byte).
  const auto shown_width = [](const std::string& s) {
    size_t n = 0;
    for (unsigned char c : s) n += (c & 0xC0) != 0x80;
    return n;
  };
  EXPECT_EQ(shown_width(first), shown_width(header)) << table;
}

// Every flag a record carries shows in the status column, with a legend line for it; a note
// of status_detail no flag explains is W, so that none goes unshown.
TEST(RunSummary, StatusShowsEveryFlagWithALegend) {
  Record plain = measured("plain", 1.0);
  Record flagged = measured("flagged", 1.0);
  flagged.set("degenerate", "reference without noise");
  flagged.set("time_target_met", false);
  flagged.set("ref_noise_target_met", false);
  flagged.set("driver_defects", "barrier_x failed");
  flagged.set("status_detail", "degenerate: reference without noise; time target missed: a repetition "
                               "stopped at its cap; reference noise target not met at the spp cap");
  EXPECT_EQ(status_cell(plain), "ok");
  EXPECT_EQ(status_cell(flagged), "ok [DTNX]");
  Record warned = measured("warned", 1.0);
  warned.set("status_detail", "scene.obj: no normals, face normals derived");
  EXPECT_EQ(status_cell(warned), "ok [W]");
  Record offset = measured("offset", 1.0);
  offset.set("ref_ray_offset_ok", false);
  EXPECT_EQ(status_cell(offset), "ok [R]");
  Record lossy = measured("lossy", 1.0);
  lossy.set("status", "lossy");
  lossy.set("status_detail", "12 fragments lost");  // the status's own reason: no W
  EXPECT_EQ(status_cell(lossy), "lossy");
  const std::string table = summary_table({plain, flagged, warned}, 10);
  EXPECT_NE(table.find("ok [DTNX]"), std::string::npos) << table;
  for (const char* legend : {"status flags: D degenerate", "T time target missed",
                             "N reference noise target missed", "X driver defects", "W another warning"})
    EXPECT_NE(table.find(legend), std::string::npos) << legend << "\n" << table;
  EXPECT_EQ(table.find("R reference ray offset"), std::string::npos) << "only the flags shown";
  EXPECT_EQ(summary_table({plain}, 10).find("status flags"), std::string::npos);
}

TEST(RunSummary, LongTablesAreCut) {
  std::vector<Record> records;
  for (int i = 0; i < 5; ++i) records.push_back(measured("c" + std::to_string(i), 1.0));
  const std::string table = summary_table(records, 3);
  EXPECT_NE(table.find("c2"), std::string::npos);
  EXPECT_EQ(table.find("c3"), std::string::npos);
  EXPECT_NE(table.find("2 more configuration(s) in records.csv"), std::string::npos) << table;
  EXPECT_EQ(summary_table({}, 3), "");
}

TEST(SweepProgress, BarCountsAndEta) {
  EXPECT_EQ(SweepProgress::format(0, 4, 0), "sweep [------------------------] 0/4 0% 0s");
  EXPECT_EQ(SweepProgress::format(1, 4, 30), "sweep [######------------------] 1/4 25% 30s, ETA 1m30s");
  EXPECT_EQ(SweepProgress::format(4, 4, 7300), "sweep [########################] 4/4 100% 2h01m");
}

}  // namespace
}  // namespace ldm
