// `ldmbench sweep FILE --memory-plan` (issue 24): the bytes it plans from the census and
// prepare() alone are the bytes a measured sweep of the same file records, buffer by buffer,
// for every structure, sizing policy and a few parameter values (tiny Cornell box: N 2,
// R_LDM 32, 32x32, one frame; seconds). Bad input exits 2 and writes nothing; a
// configuration the device cannot hold is a "refused" row, as a sweep's "failed" record.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>

#include "harness/records/record_validation.h"
#include "support/test_support.h"

namespace ldm {
namespace {

namespace fs = std::filesystem;

using test::ldmbench;
using test::Outcome;
using test::read_text;

using Row = std::map<std::string, std::string>;

// A CSV file's rows by their config_id, each as column -> text.
std::map<std::string, Row> rows_by_id(const fs::path& csv) {
  const auto table = parse_csv(read_text(csv.string()));
  std::map<std::string, Row> rows;
  if (table.empty()) return rows;
  for (size_t i = 1; i < table.size(); ++i) {
    Row row;
    for (size_t c = 0; c < table[0].size() && c < table[i].size(); ++c) row[table[0][c]] = table[i][c];
    rows[row["config_id"]] = row;
  }
  return rows;
}

// "table=123;offsets=45" as buffer -> bytes.
std::map<std::string, std::string> buffers_of(const std::string& text) {
  std::map<std::string, std::string> buffers;
  size_t start = 0;
  while (start < text.size()) {
    size_t end = text.find(';', start);
    if (end == std::string::npos) end = text.size();
    const std::string item = text.substr(start, end - start);
    const size_t equals = item.find('=');
    buffers[item.substr(0, equals)] = item.substr(equals + 1);
    start = end + 1;
  }
  return buffers;
}

std::string write_sweep_file(const fs::path& dir, const std::string& name, const std::string& text) {
  const fs::path path = dir / name;
  std::ofstream(path) << text;
  return path.string();
}

// The plan's rows (from --out) and the measured records of the same sweep file.
struct PlanAndRun {
  std::map<std::string, Row> plan, records;
};

PlanAndRun plan_and_measure(const std::string& sweep_text) {
  const fs::path dir = test::make_temp_dir("ldm-memory-plan");
  const std::string sweep = write_sweep_file(dir, "sweep.json", sweep_text);
  const Outcome planned = ldmbench("sweep " + sweep + " --memory-plan --out " + (dir / "plan").string());
  EXPECT_EQ(planned.status, 0) << planned.output;
  const Outcome measured = ldmbench("sweep " + sweep + " --out " + (dir / "run").string());
  EXPECT_EQ(measured.status, 0) << measured.output;
  return {rows_by_id(dir / "plan" / "memory-plan.csv"), rows_by_id(dir / "run" / "records.csv")};
}

// Every measured configuration has a planned row with the record's census, bytes_allocated
// and every buffer's mem_<buffer>_allocated.
void expect_plan_matches_records(const PlanAndRun& result) {
  ASSERT_FALSE(result.records.empty());
  EXPECT_EQ(result.plan.size(), result.records.size());
  for (const auto& [id, record] : result.records) {
    SCOPED_TRACE(id);
    ASSERT_TRUE(result.plan.count(id));
    const Row& plan = result.plan.at(id);
    EXPECT_EQ(plan.at("status"), "planned") << plan.at("status_detail");
    EXPECT_EQ(plan.at("bytes_allocated"), record.at("bytes_allocated"));
    if (record.at("structure") != "none") {
      EXPECT_EQ(plan.at("fragments"), record.at("fragments"));
      EXPECT_EQ(plan.at("max_depth_complexity"), record.at("max_depth_complexity"));
    }
    const auto buffers = buffers_of(plan.at("buffers"));
    for (const auto& [name, bytes] : buffers) EXPECT_EQ(bytes, record.at("mem_" + name + "_allocated")) << name;
    // No buffer the record has is missing from the plan.
    for (const auto& [column, value] : record)
      if (column.rfind("mem_", 0) == 0 && column.size() > 14 &&
          column.compare(column.size() - 10, 10, "_allocated") == 0 && !value.empty())
        EXPECT_TRUE(buffers.count(column.substr(4, column.size() - 14))) << column;
    // A fixed array's k below the deepest pixel loses fragments: the plan says so before
    // the run does.
    if (!plan.at("lossy").empty())
      EXPECT_EQ(plan.at("lossy") == "true", record.at("status") == "lossy") << record.at("status_detail");
  }
}

const std::string kSettings =
    R"("r_ldm": 32, "views": 2, "image_size": "32x32", "frames": 1, "warmup": 0},
    "settings": {"reference": {"enabled": false}, "images": false, "timing": {"target": 0}}})";

TEST(MemoryPlanCli, OracleBytesAreTheRecordedBytesForEveryStructureAndParameter) {
  const PlanAndRun result = plan_and_measure(
      R"({"axes": {"structures": "all", "passes": ["ao", "hbao", "rtao"], "sizing": "oracle",)"
      R"("habuffer:load_factor": [0.5, 2], "ppfla:k": [0, 2], "psppfla:k": [0, 3], )" + kSettings);
  // psppsll, ppsll, dfbuffer + 2 habuffer + 2 ppfla + 2 psppfla + hbao + rtao.
  EXPECT_EQ(result.records.size(), 9u + 2u);
  expect_plan_matches_records(result);
  EXPECT_EQ(result.plan.at("cornell-ppfla-ao-n2-r32-plane-k=2-oracle").at("lossy"), "true");
}

TEST(MemoryPlanCli, CensusPreviousFrameAndBudgetBytesAreTheRecordedBytes) {
  // Under census and previous_frame the storage grows in the first frame; the plan grows it
  // the same way. On the Cornell box previous_frame's first guess (1 fragment per LDM pixel)
  // holds; in the hairball it overflows and grows. One build (as here) and several (below)
  // record different bytes for the HA-buffer whose guess held: the plan follows the run's.
  const PlanAndRun result = plan_and_measure(
      R"({"include": [{"scenes": "hairball", "sizing": "previous_frame"}],)"
      R"("axes": {"structures": "all", "sizing": ["census", "previous_frame", "budget"],)"
      R"("sizing_budget_mib": 0.1, )" + kSettings);
  EXPECT_EQ(result.records.size(), 6u * 3u + 6u);
  expect_plan_matches_records(result);
}

TEST(MemoryPlanCli, PreviousFrameBytesAfterSeveralBuildsAreTheRecordedBytes) {
  // Three builds: the HA-buffer leaves its held guess at the second (its third counter word
  // freed, 4 bytes less than after one build); every structure's plan is what the run records.
  std::string settings = kSettings;
  const std::string one_build = R"("frames": 1, "warmup": 0)";
  settings.replace(settings.find(one_build), one_build.size(), R"("frames": 2, "warmup": 1)");
  const PlanAndRun several = plan_and_measure(
      R"({"axes": {"structures": "all", "sizing": "previous_frame", )" + settings);
  EXPECT_EQ(several.records.size(), 6u);
  expect_plan_matches_records(several);
  const PlanAndRun one = plan_and_measure(
      R"({"axes": {"structures": "habuffer", "sizing": "previous_frame", )" + kSettings);
  const std::string id = "cornell-habuffer-ao-n2-r32-plane-prevframe";
  ASSERT_TRUE(several.plan.count(id) && one.plan.count(id));
  EXPECT_EQ(std::stoll(one.plan.at(id).at("bytes_allocated")) - std::stoll(several.plan.at(id).at("bytes_allocated")), 4);
}

TEST(MemoryPlanCli, BadInputWritesNothingAndRefusalsAreRows) {
  const fs::path dir = test::make_temp_dir("ldm-memory-plan");
  const fs::path out = dir / "plan";
  const std::string bad = write_sweep_file(dir, "bad.json", R"({"axes": {"structures": ["psppsll", "foo"]}})");
  const Outcome unknown = ldmbench("sweep " + bad + " --memory-plan --out " + out.string());
  EXPECT_EQ(unknown.status, 2) << unknown.output;
  EXPECT_NE(unknown.output.find("bad.json: axes.structures[1]: unknown structure \"foo\""), std::string::npos)
      << unknown.output;
  EXPECT_FALSE(fs::exists(out));

  // A buffer over the storage block (k = 100000: 782 MiB) and a budget below the fixed
  // buffers are refused, with the run's reason; the others are planned.
  const std::string sweep = write_sweep_file(
      dir, "refused.json",
      R"({"axes": {"structures": ["ppfla", "dfbuffer"], "sizing": ["oracle", "budget"],)"
      R"("sizing_budget_mib": 0.001, "ppfla:k": [4, 100000], )" + kSettings);
  const Outcome file_as_out = ldmbench("sweep " + sweep + " --memory-plan --out " + bad);
  EXPECT_EQ(file_as_out.status, 2) << file_as_out.output;
  EXPECT_EQ(ldmbench("sweep " + sweep + " --memory-plan --dry-run").status, 2);
  // Options about measuring or resuming would be ignored: refused instead.
  EXPECT_EQ(ldmbench("sweep " + sweep + " --memory-plan --repetitions 2").status, 2);
  EXPECT_FALSE(fs::exists(out));

  const Outcome refused = ldmbench("sweep " + sweep + " --memory-plan --out " + out.string());
  EXPECT_EQ(refused.status, 3) << refused.output;  // as a sweep with failed configurations
  const auto rows = rows_by_id(out / "memory-plan.csv");
  ASSERT_EQ(rows.size(), 6u) << refused.output;
  for (const std::string sizing : {"oracle", "budget0.001"}) {
    const Row& too_big = rows.at("cornell-ppfla-ao-n2-r32-plane-k=100000-" + sizing);
    EXPECT_EQ(too_big.at("status"), "refused");
    EXPECT_NE(too_big.at("status_detail").find("GL_MAX_SHADER_STORAGE_BLOCK_SIZE"), std::string::npos);
    EXPECT_EQ(too_big.at("bytes_allocated"), "");  // not 0 bytes: nothing fits
    EXPECT_EQ(rows.at("cornell-ppfla-ao-n2-r32-plane-k=4-" + sizing).at("status"), "planned");
  }
  EXPECT_EQ(rows.at("cornell-dfbuffer-ao-n2-r32-plane-oracle").at("status"), "planned");
  const Row& over_budget = rows.at("cornell-dfbuffer-ao-n2-r32-plane-budget0.001");
  EXPECT_EQ(over_budget.at("status"), "refused");
  EXPECT_NE(over_budget.at("status_detail").find("does not hold its fixed buffers"), std::string::npos);
  // stdout carries the same CSV (the header at least, and every row's id).
  EXPECT_NE(refused.output.find("config_id,scene,structure"), std::string::npos);

  // A shard plans its own configurations only.
  const Outcome shard = ldmbench("sweep " + sweep + " --memory-plan --shard 1/3 --out " + (dir / "shard").string());
  EXPECT_EQ(rows_by_id(dir / "shard" / "memory-plan.csv").size(), 2u) << shard.output;
}

}  // namespace
}  // namespace ldm
