// Extremes of `ldmbench run` (issue 12): numbers that only go wrong as 32-bit floats, a
// cache path that is a file, a configuration with nothing in view, reruns into the same
// folder, kills, and a reference whose ray offset is not small against d_max.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "support/test_support.h"

namespace ldm {
namespace {

namespace fs = std::filesystem;

using test::Outcome;

using test::ldmbench;

using test::read_text;

size_t count_lines(const std::string& text, const std::string& prefix = "") {
  size_t n = 0;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) n += line.rfind(prefix, 0) == 0;
  return n;
}

// The three views of one run folder: journal entries, CSV rows, JSON records.
struct Tables {
  size_t journal_records, csv_rows, json_records;
};
Tables tables(const fs::path& out) {
  return {count_lines(read_text(out / "records.jsonl"), "{\"record\":"),
          count_lines(read_text(out / "records.csv")) - 1,
          nlohmann::json::parse(read_text(out / "records.json"))["records"].size()};
}

// Every view of the run folder holds `n` records.
void expect_records(const fs::path& out, size_t n) {
  const Tables t = tables(out);
  EXPECT_EQ(t.journal_records, n);
  EXPECT_EQ(t.csv_rows, n);
  EXPECT_EQ(t.json_records, n);
}

std::vector<std::string> hidden_files(const fs::path& dir) {
  std::vector<std::string> names;
  for (const auto& entry : fs::recursive_directory_iterator(dir))
    if (entry.path().filename().string().front() == '.') names.push_back(entry.path().string());
  return names;
}

const std::string kFast = "-R 8 --width 16 --height 16 --frames 1 --warmup 0 ";

TEST(ExtremesCli, NumbersAreCheckedAsTheFloatsTheRunUses) {
  // Each used to reach the GPU: failed records, exit 3, orphan images (or with
  // --no-reference an ok record of an inf/0/NaN d_max); --normal-offset nan was ignored.
  test::expect_run_rejected(kFast + "--d-max nan", "--d-max");
  test::expect_run_rejected(kFast + "--d-max 1e-50", "--d-max");
  test::expect_run_rejected(kFast + "--d-max 1e39", "--d-max");
  test::expect_run_rejected(kFast + "--normal-offset nan", "--normal-offset");
  test::expect_run_rejected(kFast + "--reference-noise nan", "--reference-noise");
  test::expect_run_rejected(kFast + "--reference-spp 8192", "--reference-max-spp");
  // A doubled comma was dropped without a word.
  test::expect_run_rejected(kFast + "-N 4,,8", "empty item");
  test::expect_run_rejected(kFast + "--scene cornell,", "empty item");
  // A JSON number beyond double: exit 2 (was 1) with the file and line.
  const std::string dir = test::make_temp_dir("ldm-extremes");
  const std::string scene = (fs::path(dir) / "e400.json").string();
  std::ofstream(scene) << "{\"generator\": {\"type\": \"cornell\"},\n\"ao\": {\"d_max\": 1e400}}\n";
  test::expect_run_rejected(kFast + "--scene " + scene, "e400.json: malformed JSON at line 2");
}

TEST(ExtremesCli, CacheDirThatIsAFileIsRejectedUpFront) {
  const std::string dir = test::make_temp_dir("ldm-extremes");
  const std::string file = (fs::path(dir) / "cache").string();
  std::ofstream(file) << "not a folder\n";
  test::expect_run_rejected(kFast + "--cache-dir " + file, "--cache-dir");
  test::expect_run_rejected(kFast + "--cache-dir " + file + "/below", "is not a folder");
}

TEST(ExtremesCli, NoFragmentInViewIsNeverOk) {
  // A triangle edge-on to the only LDM view (N = 1 looks along the pole, which lies in the
  // triangle's plane): the census counts 0 fragments, every build check passes vacuously.
  const std::string dir = test::make_temp_dir("ldm-extremes");
  std::ofstream(fs::path(dir) / "edge.obj") << "v 0 0 0\nv 0 1 0\nv 0 0 1\nf 1 2 3\n";
  std::ofstream(fs::path(dir) / "edge.json")
      << R"({"meshes": [{"file": "edge.obj"}], "camera": {"eye": [3, 0.3, 0.3], "target": [0, 0.3, 0.3]}})";
  const fs::path out = fs::path(dir) / "out";
  const Outcome o = ldmbench("run --scene " + (fs::path(dir) / "edge.json").string() + " -N 1 " +
                             kFast + "--no-reference --out " + out.string());
  EXPECT_EQ(o.status, 3) << o.output;
  const auto r = nlohmann::json::parse(read_text(out / "records.json"))["records"][0];
  EXPECT_EQ(r["fragments"], 0);
  EXPECT_EQ(r["status"], "invalid");
  EXPECT_NE(r["status_detail"].get<std::string>().find("no fragment"), std::string::npos);
}

TEST(ExtremesCli, RerunResumesTheSameSweepAndRefusesAnother) {
  const fs::path out = fs::path(test::make_temp_dir("ldm-extremes")) / "sweep";
  const std::string sweep = "run -N 2,4 " + kFast + "--no-reference --out " + out.string();
  ASSERT_EQ(ldmbench(sweep).status, 0);
  ASSERT_EQ(tables(out).journal_records, 2u);
  // The same command again measures nothing and keeps both rows (it used to re-measure
  // everything, and a kill during that rerun lost complete rows).
  const Outcome again = ldmbench(sweep);
  EXPECT_EQ(again.status, 0) << again.output;
  EXPECT_NE(again.output.find("resuming: 2"), std::string::npos) << again.output;
  EXPECT_EQ(again.output.find("[1/2]"), std::string::npos) << again.output;
  expect_records(out, 2);
  // Another sweep into the same folder is refused and changes nothing ...
  const std::string before = read_text(out / "records.jsonl");
  const Outcome other = ldmbench("run -N 8 " + kFast + "--no-reference --out " + out.string());
  EXPECT_EQ(other.status, 2) << other.output;
  EXPECT_NE(other.output.find("--overwrite"), std::string::npos) << other.output;
  EXPECT_EQ(read_text(out / "records.jsonl"), before);
  // ... unless asked to replace it.
  const Outcome replaced =
      ldmbench("run -N 8 " + kFast + "--no-reference --overwrite --out " + out.string());
  EXPECT_EQ(replaced.status, 0) << replaced.output;
  EXPECT_EQ(tables(out).journal_records, 1u);
  // A folder that holds something other than a run is refused too.
  const fs::path foreign = fs::path(test::make_temp_dir("ldm-extremes")) / "foreign";
  fs::create_directories(foreign);
  std::ofstream(foreign / "notes.txt") << "mine\n";
  EXPECT_EQ(ldmbench("run " + kFast + "--no-reference --out " + foreign.string()).status, 2);
  EXPECT_TRUE(fs::exists(foreign / "notes.txt"));
}

TEST(ExtremesCli, AKilledRunIsRepairedFromItsJournal) {
  const fs::path out = fs::path(test::make_temp_dir("ldm-extremes")) / "killed";
  const std::string sweep = "run -N 2,4,8 " + kFast + "--no-reference --out " + out.string();
  ASSERT_EQ(ldmbench(sweep).status, 0);
  // What a SIGKILL can leave: the last journal line torn, the CSV one row ahead of the JSON,
  // a hidden temporary image.
  std::string journal = read_text(out / "records.jsonl");
  const size_t last = journal.rfind("{\"record\":");
  journal = journal.substr(0, last + 40);  // the third record, cut mid-line
  std::ofstream(out / "records.jsonl", std::ios::trunc) << journal;
  std::ofstream(out / "records.csv", std::ios::app) << "extra,row\n";
  std::ofstream(out / "images" / ".cornell-psppsll-ao-n8-r8-ao.tmp4242.exr") << "half";
  const Outcome resumed = ldmbench(sweep);
  EXPECT_EQ(resumed.status, 0) << resumed.output;
  EXPECT_NE(resumed.output.find("resuming: 2"), std::string::npos) << resumed.output;
  EXPECT_NE(resumed.output.find("[3/3]"), std::string::npos) << resumed.output;
  expect_records(out, 3);
  EXPECT_TRUE(hidden_files(out).empty()) << hidden_files(out).front();
  // Every journal line is whole JSON again.
  std::istringstream lines(read_text(out / "records.jsonl"));
  for (std::string line; std::getline(lines, line);) EXPECT_NO_THROW(nlohmann::json::parse(line));
}

TEST(ExtremesCli, SigtermAbandonsTheConfigurationInFlightAndExitsDistinctly) {
  const fs::path dir = test::make_temp_dir("ldm-extremes");
  const fs::path out = dir / "term", log = dir / "log";
  // A reference of 2^18 samples per pixel takes far longer than the test: the signal lands
  // while the first configuration is in flight (its AO image already written).
  const std::string command = std::string(LDM_BINARY_PATH) + " run -N 2,4 " + kFast +
                              "--reference-spp 262144 --reference-max-spp 262144 --cache-dir " + (dir / "cache").string() +
                              " --out " + out.string();
  const std::string script =
      "(" + command + " > " + log.string() + " 2>&1 & pid=$!; "
      "for i in $(seq 300); do grep -q '\\[1/2\\]' " + log.string() + " && break; sleep 0.1; done; "
      "sleep 1; kill -TERM $pid; wait $pid; echo \"exit=$?\")";
  std::string output;
  test::run_command(script, &output);
  const std::string logged = read_text(log);
  EXPECT_NE(output.find("exit=143"), std::string::npos) << output << logged;
  EXPECT_NE(logged.find("abandoned"), std::string::npos) << logged;
  EXPECT_NE(logged.find("interrupted by signal 15"), std::string::npos) << logged;
  expect_records(out, 0);  // the CSV: its header alone
  for (const auto& entry : fs::directory_iterator(out / "images"))
    ADD_FAILURE() << "orphan image " << entry.path();
  EXPECT_TRUE(hidden_files(out).empty());
}

TEST(ExtremesCli, ReferenceRayOffsetLargeAgainstDmaxIsFlagged) {
  const std::string cache = test::make_temp_dir("ldm-extremes");
  const fs::path out = fs::path(test::make_temp_dir("ldm-extremes")) / "offset";
  // d_max 1e-6 on the Cornell box (5.6 units): the offset (~3e-5) exceeds d_max itself.
  const Outcome o = ldmbench("run -N 2 " + kFast + "--d-max 1e-6,1 --reference-spp 4 --cache-dir " +
                             cache + " --out " + out.string());
  ASSERT_EQ(o.status, 0) << o.output;
  const auto records = nlohmann::json::parse(read_text(out / "records.json"))["records"];
  ASSERT_EQ(records.size(), 2u);
  EXPECT_FALSE(records[0]["ref_ray_offset_ok"].get<bool>());
  EXPECT_GT(records[0]["ref_ray_offset"].get<double>(), 1e-6);
  EXPECT_NE(records[0]["status_detail"].get<std::string>().find("ray offset"), std::string::npos);
  EXPECT_TRUE(records[1]["ref_ray_offset_ok"].get<bool>());
  EXPECT_LT(records[1]["ref_ray_offset"].get<double>(), 1e-4);
}

}  // namespace
}  // namespace ldm
