// `ldmbench advise` (issue 24): the search on synthetic models (Python's unittest,
// tests/advise/test_search.py), the refusals of bad budgets and empty spaces, and a small
// advise end to end on the Cornell box: answered, verified with its record, reported,
// journaled, and resumed by a rerun without measuring again.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "support/test_support.h"

namespace ldm {
namespace {

namespace fs = std::filesystem;
using test::ldmbench;
using test::Outcome;

size_t count_records(const fs::path& path) {
  std::ifstream in(path);
  size_t n = 0;
  for (std::string line; std::getline(in, line);) n += line.rfind("{\"record\":", 0) == 0;
  return n;
}

// Records in every stage's records.jsonl (a resumed sweep adds a "run" line, no record).
size_t measured_records(const fs::path& out) {
  size_t n = 0;
  if (!fs::exists(out / "stages")) return 0;
  for (const auto& stage : fs::directory_iterator(out / "stages"))
    if (fs::exists(stage.path() / "run" / "records.jsonl")) n += count_records(stage.path() / "run" / "records.jsonl");
  return n;
}

TEST(AdviseSearch, SearchOnSyntheticModels) {
  const Outcome o = test::run_shell(std::string(LDM_PYTHON) + " " + LDM_TEST_SOURCE_DIR + "/advise/test_search.py");
  EXPECT_EQ(o.status, 0) << o.output;
  EXPECT_NE(o.output.find("OK"), std::string::npos) << o.output;
}

TEST(AdviseCli, RefusesBadBudgetsAndEmptySpacesWithNothingWritten) {
  const fs::path dir = test::make_temp_dir("advise-refusals");
  std::ofstream(dir / "empty.json") << R"({"axes": {"structures": "ppfla", "views": []}})";
  std::ofstream(dir / "fixed.json") << R"({"axes": {"image_size": "32x32"}})";
  std::ofstream(dir / "owner.json") << R"({"axes": {"nosuch:k": [1]}})";
  std::ofstream(dir / "broken.json") << "{\"axes\": {\n  \"views\": [4,\n}";
  std::ofstream(dir / "outside.json") << R"({"axes": {"structures": "psppsll"}})";
  const std::string out = (dir / "out").string();
  const struct {
    std::string args, message;
  } cases[] = {
      {"--budget-ms -1", "--budget-ms -1: expected a positive finite number"},
      {"--budget-ms 0", "--budget-ms 0: expected a positive finite number"},
      {"--budget-mib nan", "--budget-mib nan: expected a positive finite number"},
      {"", "no budget"},
      {"--max-error 0.1 --min-mssim 0.9", "give one error bound, not both"},
      {"--min-mssim 1.5", "--min-mssim 1.5: expected a number in (0, 1]"},
      {"--budget-ms 10 --structures nosuch", "unknown structure \"nosuch\""},
      {"--budget-ms 10 --space " + (dir / "missing.json").string(), "no such file"},
      {"--budget-ms 10 --space " + (dir / "empty.json").string(), "axes.views: no values"},
      {"--budget-ms 10 --space " + (dir / "fixed.json").string(), "axes.image_size: fixed by the question"},
      {"--budget-ms 10 --space " + (dir / "owner.json").string(), "axes.nosuch:k: unknown owner"},
      {"--budget-ms 10 --space " + (dir / "broken.json").string(), "line 3 column 1"},
      {"--budget-ms 10 --structures ppfla --space " + (dir / "outside.json").string(),
       "none of --structures ppfla is in the space"},
      {"--budget-ms 10 --scene nosuchscene", "'nosuchscene' is neither a built-in scene"},
      {"--budget-ms 10 --shards 0", "--shards: Value 0 not in range 1 to 4096"},
      {"--budget-ms 10 --launcher pbs", "--launcher: pbs not in {local,slurm}"},
  };
  for (const auto& c : cases) {
    const std::string scene = c.args.find("--scene") == std::string::npos ? "--scene cornell " : "";
    const Outcome o = ldmbench("advise " + scene + c.args + " --out " + out);
    EXPECT_EQ(o.status, 2) << c.args << "\n" << o.output;
    EXPECT_NE(o.output.find(c.message), std::string::npos) << c.args << "\n" << o.output;
    EXPECT_FALSE(fs::exists(out)) << c.args;
  }
}

// A small space on the Cornell box at 32x32: answered and verified, then rerun (resumed:
// nothing measured again), then asked another question in the same folder (refused), then
// an infeasible memory budget (no recommendation, exit 1, every candidate's reason).
// The method as an axis (issue 36): LDM AO beside GTAO and GPU RTAO in one question, each
// peer a candidate per value of its own parameters, all scored against one reference.
TEST(AdviseEndToEnd, ChoosesAmongAoMethods) {
  const fs::path dir = test::make_temp_dir("advise-methods");
  std::ofstream(dir / "space.json") << R"({"axes": {"structures": ["psppsll"], "views": [4, 8], "r_ldm": [32],
                                                    "gtao:slices": [2, 4], "rtao_gpu:spp": [1, 4]}})";
  const fs::path out = dir / "advice";
  const Outcome o = ldmbench("advise --scene cornell --pass ao,gtao,rtao_gpu --space " + (dir / "space.json").string() +
                             " --image-size 32x32 --reference-max-spp 16 --levels 1 --budget-ms 1000 --cache-dir " +
                             (dir / "cache").string() + " --out " + out.string());
  ASSERT_EQ(o.status, 0) << o.output;
  const auto result = nlohmann::json::parse(test::read_text((out / "result.json").string()));
  EXPECT_EQ(result["configurations"].get<size_t>(), 6u);  // psppsll 2, gtao 2, rtao_gpu 2
  // Every method was measured (the brief stage's records name each pass).
  std::string measured;
  for (const auto& entry : fs::recursive_directory_iterator(out / "stages"))
    if (entry.path().filename() == "records.csv") measured += test::read_text(entry.path().string());
  for (const char* id : {"cornell-psppsll-ao-n", "cornell-none-gtao-slices=", "cornell-none-rtao_gpu-spp="})
    EXPECT_NE(measured.find(id), std::string::npos) << id;
  const std::string recommended = result["recommended"];
  EXPECT_EQ(recommended.rfind("cornell-", 0), 0u) << recommended;
  // A mixed question across kinds of reference is refused, naming the option.
  const Outcome mixed = ldmbench("advise --scene cornell --pass ao,indirect --budget-ms 10 --out " + (dir / "mixed").string());
  EXPECT_EQ(mixed.status, 2) << mixed.output;
  EXPECT_NE(mixed.output.find("--pass ao,indirect: only the AO passes"), std::string::npos) << mixed.output;
}

TEST(AdviseEndToEnd, SmallAdviseOnTheCornellBox) {
  const fs::path dir = test::make_temp_dir("advise-e2e");
  std::ofstream(dir / "space.json")
      << R"({"axes": {"structures": ["psppsll", "habuffer", "ppfla"], "views": [2, 4, 8], "r_ldm": [16, 32],
                      "ppfla:k": [2, 8]}})";
  const fs::path out = dir / "advice";
  const std::string common = "advise --scene cornell --space " + (dir / "space.json").string() +
                             " --image-size 32x32 --reference-max-spp 16 --levels 2 --cache-dir " +
                             (dir / "cache").string();
  const std::string question = common + " --budget-ms 1000 --budget-mib 0.25 --out " + out.string();
  const Outcome first = ldmbench(question);
  ASSERT_EQ(first.status, 0) << first.output;
  EXPECT_NE(first.output.find("Recommended: **cornell-"), std::string::npos) << first.output;

  const auto result = nlohmann::json::parse(test::read_text((out / "result.json").string()));
  const std::string recommended = result["recommended"];
  EXPECT_LE(result["verified"]["bytes_allocated"].get<double>(), 0.25 * 1048576);
  EXPECT_TRUE(result["verified"]["within_budgets_surely"].get<bool>()) << result.dump(1);
  // cheap first: fewer configurations measured briefly than the space holds
  const size_t space_size = result["configurations"];
  EXPECT_EQ(space_size, 24u);  // psppsll 6, habuffer 6, ppfla 2 x 6
  EXPECT_FALSE(result["pruned"].empty());
  // the census plans every configuration's memory without building it, and every brief
  // measurement allocated exactly what it planned
  EXPECT_EQ(result["planned"].get<size_t>(), space_size);
  EXPECT_TRUE(fs::exists(out / "stages" / "01-census" / "plan" / "memory-plan.csv"));
  EXPECT_TRUE(result["plan_differs"].empty()) << result["plan_differs"].dump();
  // the lossy k = 2 arrays never recommended; every pruned candidate says why
  EXPECT_EQ(recommended.find("k=2"), std::string::npos);
  for (const auto& [key, why] : result["pruned"].items()) EXPECT_FALSE(why.get<std::string>().empty()) << key;
  // verified with its record written at a normal run's precision
  const fs::path verify = result["verified"]["folder"].get<std::string>();
  const std::string records = test::read_text((verify / "run" / "records.csv").string());
  EXPECT_NE(records.find(recommended), std::string::npos);
  EXPECT_NE(test::read_text((verify / "sweep.json").string()).find("\"target\": 0.03"), std::string::npos);
  // explained and journaled
  const std::string summary = test::read_text((out / "report" / "summary.md").string());
  for (const char* part : {"## Front found", "## Pruned, and why", "## Time spent", "(recommended)"})
    EXPECT_NE(summary.find(part), std::string::npos) << part << "\n" << summary;
  EXPECT_GT(fs::file_size(out / "report" / "front.png"), 1000u);
  // One source for the counts (issue 37): the console's counts line is summary.md's, word
  // for word, and its stages are the folders that measured (the census plans, apart).
  const size_t at = first.output.find("The census planned");
  ASSERT_NE(at, std::string::npos) << first.output;
  const std::string counts_line = first.output.substr(at, first.output.find("; report: ", at) - at);
  EXPECT_NE(summary.find(counts_line + "."), std::string::npos) << counts_line << "\n" << summary;
  size_t measuring_stages = 0;
  for (const auto& stage : fs::directory_iterator(out / "stages"))
    if (stage.path().filename().string().find("census") == std::string::npos) ++measuring_stages;
  EXPECT_EQ(result["counts"]["stages"].get<size_t>(), measuring_stages) << result["counts"].dump();
  EXPECT_NE(counts_line.find(std::to_string(measuring_stages) + " measuring stage"), std::string::npos) << counts_line;
  const std::string journal = test::read_text((out / "advise.jsonl").string());
  EXPECT_NE(journal.find("\"event\": \"started\""), std::string::npos);
  EXPECT_NE(journal.find("\"event\": \"pruned\""), std::string::npos);

  // Sharded (--shards 2, local): every measured stage in two shards, merged; the census's
  // plan and the first exploration stage (the same configurations whatever the timings)
  // equal the unsharded ones, the stage in every column that is not time.
  const fs::path sharded = dir / "sharded";
  const Outcome in_shards = ldmbench(common + " --budget-ms 1000 --budget-mib 0.25 --shards 2 --out " + sharded.string());
  ASSERT_EQ(in_shards.status, 0) << in_shards.output;
  EXPECT_EQ(test::read_text((sharded / "stages" / "01-census" / "plan" / "memory-plan.csv").string()),
            test::read_text((out / "stages" / "01-census" / "plan" / "memory-plan.csv").string()));
  EXPECT_TRUE(fs::exists(sharded / "stages" / "02-explore-0" / "shards-2" / "shard-1" / "records.csv"));
  const Outcome same = test::run_shell(std::string(LDM_PYTHON) + " " + LDM_TEST_SOURCE_DIR + "/../scripts/same_records.py " +
                                       (out / "stages" / "02-explore-0" / "run").string() + " " +
                                       (sharded / "stages" / "02-explore-0" / "shards-2" / "merged").string());
  EXPECT_EQ(same.status, 0) << same.output;
  const auto result_sharded = nlohmann::json::parse(test::read_text((sharded / "result.json").string()));
  EXPECT_NE(result_sharded["verified"]["records"].get<std::string>().find("shards-"), std::string::npos);

  // Resumed: the same question into the same folder measures nothing again.
  const size_t before = measured_records(out);
  const Outcome again = ldmbench(question);
  ASSERT_EQ(again.status, 0) << again.output;
  EXPECT_EQ(measured_records(out), before);
  const auto result2 = nlohmann::json::parse(test::read_text((out / "result.json").string()));
  EXPECT_EQ(result2["recommended"], recommended);
  EXPECT_TRUE(result2["resumed"].get<bool>());

  // Another question into that folder is refused, nothing changed.
  const Outcome other = ldmbench(common + " --budget-ms 500 --out " + out.string());
  EXPECT_EQ(other.status, 2) << other.output;
  EXPECT_NE(other.output.find("holds another advise"), std::string::npos) << other.output;
  EXPECT_EQ(measured_records(out), before);

  // An infeasible budget: no recommendation, exit 1, a reason for every candidate.
  const Outcome none =
      ldmbench(common + " --structures psppsll --budget-mib 0.0001 --out " + (dir / "none").string());
  EXPECT_EQ(none.status, 1) << none.output;
  EXPECT_NE(none.output.find("No configuration of the space meets the budgets"), std::string::npos) << none.output;
  const auto result3 = nlohmann::json::parse(test::read_text((dir / "none" / "result.json").string()));
  EXPECT_TRUE(result3["recommended"].is_null());
  EXPECT_EQ(result3["pruned"].size(), 6u);
  // over the budget by the census's plan: nothing measured
  EXPECT_EQ(result3["measured"].get<int>(), 0) << result3.dump(1);
  for (const auto& [key, why] : result3["pruned"].items())
    EXPECT_EQ(why.get<std::string>().rfind("memory (census)", 0), 0u) << key << ": " << why;
}

// Killed (SIGKILL, the whole process group) in the middle of a stage, after its sweep
// recorded a configuration and before it recorded them all, then rerun: the rerun resumes
// that stage's sweep (the recorded configurations are not measured again) and answers.
TEST(AdviseEndToEnd, KilledMidStageResumes) {
  const fs::path dir = test::make_temp_dir("advise-kill");
  std::ofstream(dir / "space.json")
      << R"({"axes": {"structures": ["psppsll", "habuffer", "ppfla"], "views": [2, 4, 8], "r_ldm": [16, 32],
                      "ppfla:k": [8]}})";
  const fs::path out = dir / "advice";
  const std::string args = "advise --scene cornell --space " + (dir / "space.json").string() +
                           " --image-size 32x32 --reference-max-spp 16 --cache-dir " + (dir / "cache").string() +
                           " --budget-ms 1000 --budget-mib 0.25 --out " + out.string();
  // The first exploration stage measures several configurations: stop the advise (SIGSTOP
  // on its group) each time its sweep has a record, kill it when 1 <= records < all.
  const fs::path stage = out / "stages" / "02-explore-0";
  std::ofstream(dir / "kill.sh") << R"(set -u
setsid "$1" $2 >"$3" 2>&1 &
pid=$!
journal="$4/run/records.jsonl"
spec="$4/sweep.json"
for i in $(seq 1 6000); do
  kill -0 $pid 2>/dev/null || { echo "advise ended before it could be killed"; exit 1; }
  if [ -f "$journal" ] && [ -f "$spec" ]; then
    kill -STOP -- -$pid
    have=$(grep -c '^{"record":' "$journal" || true)
    total=$(sed -n 's/.*stage explore-0: \([0-9]*\) configurations.*/\1/p' "$spec")
    if [ "$have" -ge 1 ] && [ "$have" -lt "${total:-0}" ]; then
      kill -KILL -- -$pid; wait $pid 2>/dev/null
      echo "killed after $have of $total"; exit 0
    fi
    kill -CONT -- -$pid
  fi
  sleep 0.01
done
echo "never in the middle of the stage"; kill -KILL -- -$pid; exit 1
)";
  const Outcome kill = test::run_shell("bash " + (dir / "kill.sh").string() + " " + LDM_BINARY_PATH + " '" + args +
                                       "' " + (dir / "first.log").string() + " " + stage.string());
  ASSERT_EQ(kill.status, 0) << kill.output << test::read_text((dir / "first.log").string());
  EXPECT_FALSE(fs::exists(out / "result.json"));

  const Outcome rerun = ldmbench(args);
  ASSERT_EQ(rerun.status, 0) << rerun.output;
  const std::string log = test::read_text((stage / "sweep.log").string());
  // "killed after K of T": the rerun's sweep resumes exactly those K records.
  const size_t after = kill.output.find("killed after ");
  ASSERT_NE(after, std::string::npos) << kill.output;
  const std::string recorded = kill.output.substr(after + 13, kill.output.find(' ', after + 13) - after - 13);
  EXPECT_NE(log.find("resuming: " + recorded + " configuration"), std::string::npos) << kill.output << "\n" << log;
  const auto result = nlohmann::json::parse(test::read_text((out / "result.json").string()));
  EXPECT_TRUE(result["resumed"].get<bool>());
  EXPECT_FALSE(result["recommended"].is_null());
}

// The indirect-light pass end to end: a space with the pass's own parameter (R_light, the
// photons emitted) besides the structures'; answered and verified, and the verified record
// is an indirect-light record of the recommended configuration with its error measured.
TEST(AdviseEndToEnd, IndirectLightOnTheCornellBox) {
  const fs::path dir = test::make_temp_dir("advise-indirect");
  std::ofstream(dir / "space.json")
      << R"({"axes": {"structures": ["psppsll", "ppfla"], "views": [2, 4], "r_ldm": [16, 32], "ppfla:k": [8],
                      "indirect:r_light": [8, 16]}})";
  const fs::path out = dir / "advice";
  const Outcome o = ldmbench("advise --scene cornell --pass indirect --space " + (dir / "space.json").string() +
                             " --image-size 32x32 --reference-max-spp 16 --cache-dir " + (dir / "cache").string() +
                             " --budget-ms 2000 --budget-mib 0.25 --out " + out.string());
  ASSERT_EQ(o.status, 0) << o.output;
  const auto result = nlohmann::json::parse(test::read_text((out / "result.json").string()));
  EXPECT_EQ(result["configurations"].get<int>(), 16);  // 2 structures x 2 N x 2 R_LDM x 2 R_light
  const std::string recommended = result["recommended"];
  EXPECT_NE(recommended.find("-indirect-"), std::string::npos) << recommended;
  EXPECT_GT(result["verified"]["error"].get<double>(), 0.0);
  const std::string records =
      test::read_text((fs::path(result["verified"]["records"].get<std::string>()) / "records.csv").string());
  EXPECT_NE(records.find(recommended), std::string::npos);
  EXPECT_NE(records.find("r_light"), std::string::npos);
}

}  // namespace
}  // namespace ldm
