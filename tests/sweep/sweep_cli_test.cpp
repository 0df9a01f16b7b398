// `ldmbench sweep` and `ldmbench merge` end to end, at the smallest sizes (N 2-8, R 32,
// 32x32 images, one frame): strict errors write nothing; a rerun skips what is finished and
// redoes failed configurations only with --redo-failed; another sweep is refused; a sweep
// killed with SIGKILL mid-run resumes to every row exactly once; shards merge into the
// whole sweep, and mismatched or overlapping runs are refused.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "support/test_support.h"

namespace ldm {
namespace {

namespace fs = std::filesystem;

using test::Outcome;

using test::ldmbench;

using test::read_text;

struct Folder {
  fs::path dir;
  std::string sweep(const std::string& name, const std::string& text) const {
    const fs::path path = dir / name;
    std::ofstream(path) << text;
    return path.string();
  }
  std::string cache() const { return " --cache-dir " + (dir / "cache").string(); }
};

Folder folder() { return {test::make_temp_dir("ldm-sweep-cli")}; }

// Three structures x two N at the smallest sizes, no reference (seconds).
const std::string kSmall = R"({"axes": {"structures": ["psppsll", "ppfla", "psppfla"],
    "views": [2, 4], "r_ldm": 32, "image_size": "32x32", "frames": 1, "warmup": 0},
    "settings": {"reference": {"enabled": false}, "images": false}})";

// The config ids of records.csv, in order (the first column).
std::vector<std::string> csv_ids(const fs::path& run) {
  std::istringstream lines(read_text(run / "records.csv"));
  std::vector<std::string> ids;
  std::string line;
  std::getline(lines, line);  // header
  while (std::getline(lines, line)) ids.push_back(line.substr(0, line.find(',')));
  return ids;
}

std::vector<nlohmann::json> journal_records(const fs::path& run) {
  std::istringstream lines(read_text(run / "records.jsonl"));
  std::vector<nlohmann::json> out;
  for (std::string line; std::getline(lines, line);) {
    const auto entry = nlohmann::json::parse(line);  // every line whole
    if (entry.contains("record")) out.push_back(entry["record"]);
  }
  return out;
}

std::vector<std::string> dry_run_ids(const std::string& sweep, const std::string& extra = "") {
  const Outcome o = ldmbench("sweep " + sweep + " --dry-run " + extra);
  EXPECT_EQ(o.status, 0) << o.output;
  std::istringstream lines(o.output);
  std::vector<std::string> ids;
  for (std::string line; std::getline(lines, line);) {
    const auto tab = line.find('\t');
    if (tab != std::string::npos) ids.push_back(line.substr(tab + 1, line.find('\t', tab + 1) - tab - 1));
  }
  return ids;
}

TEST(SweepCli, DryRunListsAndBadFilesWriteNothing) {
  const Folder f = folder();
  const std::string sweep = f.sweep("small.json", kSmall);
  EXPECT_EQ(dry_run_ids(sweep).size(), 6u);
  // A shard mixes the axes' values (harness/run/shard_assignment.h), in sweep order.
  const std::vector<std::string> shard = dry_run_ids(sweep, "--shard 1/4");
  EXPECT_EQ(shard, (std::vector<std::string>{"cornell-psppsll-ao-n2-r32-plane-prevframe",
                                             "cornell-psppfla-ao-n4-r32-plane-prevframe"}));
  const fs::path out = f.dir / "out";
  const Outcome dry = ldmbench("sweep " + sweep + " --dry-run --out " + out.string());
  EXPECT_FALSE(fs::exists(out));

  std::string broken = kSmall;
  broken.replace(broken.find("\"psppfla\""), 9, "\"foo\"");
  const Outcome bad = ldmbench("sweep " + f.sweep("bad.json", broken) + " --out " + out.string());
  EXPECT_EQ(bad.status, 2) << bad.output;
  EXPECT_NE(bad.output.find("bad.json: axes.structures[2]: unknown structure \"foo\""), std::string::npos)
      << bad.output;
  EXPECT_FALSE(fs::exists(out));
  const Outcome shard_error = ldmbench("sweep " + sweep + " --shard 4/4 --out " + out.string());
  EXPECT_EQ(shard_error.status, 2) << shard_error.output;
  EXPECT_FALSE(fs::exists(out));
}

TEST(SweepCli, RerunSkipsFinishedAnotherSweepIsRefused) {
  const Folder f = folder();
  const std::string sweep = f.sweep("small.json", kSmall);
  const fs::path out = f.dir / "run";
  const Outcome first = ldmbench("sweep " + sweep + " --out " + out.string());
  ASSERT_EQ(first.status, 0) << first.output;
  EXPECT_EQ(csv_ids(out), dry_run_ids(sweep));
  // The summary table and the next command.
  EXPECT_NE(first.output.find("configuration"), std::string::npos);
  EXPECT_NE(first.output.find("MiB alloc"), std::string::npos) << first.output;
  EXPECT_NE(first.output.find("next: ldmbench report " + out.string()), std::string::npos) << first.output;

  // The same sweep (formatted differently) measures nothing again.
  std::string reformatted = kSmall;
  reformatted.insert(1, "\n  ");
  const Outcome again = ldmbench("sweep " + f.sweep("small.json", reformatted) + " --out " + out.string());
  EXPECT_EQ(again.status, 0) << again.output;
  EXPECT_NE(again.output.find("resuming: 6"), std::string::npos) << again.output;
  EXPECT_EQ(again.output.find("[1/6]"), std::string::npos) << again.output;
  EXPECT_EQ(journal_records(out).size(), 6u);

  // Another sweep into the folder: refused, untouched; --overwrite replaces.
  std::string other = kSmall;
  other.replace(other.find("[2, 4]"), 6, "[2, 8]");
  const std::string other_sweep = f.sweep("other.json", other);
  const Outcome refused = ldmbench("sweep " + other_sweep + " --out " + out.string());
  EXPECT_EQ(refused.status, 2) << refused.output;
  EXPECT_NE(refused.output.find("different sweep"), std::string::npos) << refused.output;
  EXPECT_EQ(journal_records(out).size(), 6u);
  // A shard of the same sweep is another sweep for the folder too.
  EXPECT_EQ(ldmbench("sweep " + sweep + " --shard 0/2 --out " + out.string()).status, 2);
  const Outcome replaced = ldmbench("sweep " + other_sweep + " --overwrite --out " + out.string());
  EXPECT_EQ(replaced.status, 0) << replaced.output;
  EXPECT_EQ(csv_ids(out), dry_run_ids(other_sweep));
}

TEST(SweepCli, FailedConfigurationsAreKeptUnlessRedone) {
  const Folder f = folder();
  // A resolution whose heads alone exceed the device's storage block fails at run time.
  const int64_t block = test::gl_context().device().max_ssbo_block_bytes;
  const int too_big = int(std::ceil(std::sqrt(double(block) / 4.0 / 64))) + 1;
  const std::string sweep = f.sweep("failing.json", R"({"axes": {"views": 64, "r_ldm": [)" +
                                    std::to_string(too_big) + R"(, 16], "image_size": 32, "frames": 1,
      "warmup": 0}, "settings": {"reference": {"enabled": false}, "images": false}})");
  const fs::path out = f.dir / "run";
  const Outcome first = ldmbench("sweep " + sweep + " --out " + out.string());
  EXPECT_EQ(first.status, 3) << first.output;  // the sweep went on past the failure
  auto records = journal_records(out);
  ASSERT_EQ(records.size(), 2u);
  EXPECT_EQ(records[0]["status"], "failed");
  EXPECT_EQ(records[1]["status"], "ok");

  const Outcome kept = ldmbench("sweep " + sweep + " --out " + out.string());
  EXPECT_EQ(kept.status, 3) << kept.output;
  EXPECT_EQ(journal_records(out).size(), 2u);  // nothing measured again

  const Outcome redone = ldmbench("sweep " + sweep + " --redo-failed --out " + out.string());
  EXPECT_EQ(redone.status, 3) << redone.output;
  EXPECT_NE(redone.output.find("1 failed one(s) to redo"), std::string::npos) << redone.output;
  records = journal_records(out);
  ASSERT_EQ(records.size(), 3u);  // the failed one measured again, appended
  EXPECT_EQ(records[2]["config_id"], records[0]["config_id"]);
  // The tables hold each configuration once, the redone one in its place.
  EXPECT_EQ(csv_ids(out), dry_run_ids(sweep));
  const auto json = nlohmann::json::parse(read_text(out / "records.json"));
  EXPECT_EQ(json["records"].size(), 2u);
}

// A lossy configuration is finished (measured, its loss counted; issue 20): a rerun keeps it,
// with or without --redo-failed, which redoes failed ones only. Fails if resuming treats
// lossy records as unfinished (they would be measured again, appended to the journal).
TEST(SweepCli, LossyConfigurationsAreFinishedOnResume) {
  const Folder f = folder();
  // A fixed array of one layer on the Cornell box loses fragments: lossy, not failed.
  const std::string sweep = f.sweep("lossy.json", R"({"axes": {"structures": ["psppsll", "ppfla"],
      "views": 2, "r_ldm": 32, "image_size": "32x32", "frames": 1, "warmup": 0, "ppfla:k": 1},
      "settings": {"reference": {"enabled": false}, "images": false}})");
  const fs::path out = f.dir / "run";
  const Outcome first = ldmbench("sweep " + sweep + " --out " + out.string());
  ASSERT_EQ(first.status, 0) << first.output;  // lossy is measured: not a failure
  auto records = journal_records(out);
  ASSERT_EQ(records.size(), 2u);
  EXPECT_EQ(records[0]["status"], "ok");
  ASSERT_EQ(records[1]["status"], "lossy") << records[1]["status_detail"];
  const std::string samples = read_text(out / records[1]["frame_samples_csv"].get<std::string>());
  for (const std::string extra : {"", " --redo-failed"}) {
    const Outcome again = ldmbench("sweep " + sweep + extra + " --out " + out.string());
    EXPECT_EQ(again.status, 0) << again.output;
    EXPECT_NE(again.output.find("resuming: 2"), std::string::npos) << again.output;
    EXPECT_EQ(again.output.find("[1/"), std::string::npos) << again.output;  // nothing measured
    EXPECT_EQ(again.output.find("to redo"), std::string::npos) << again.output;
    EXPECT_EQ(journal_records(out).size(), 2u) << extra;
    EXPECT_TRUE(read_text(out / records[1]["frame_samples_csv"].get<std::string>()) == samples)
        << "the lossy configuration's frame samples were rewritten" << extra;
  }
  EXPECT_EQ(csv_ids(out), dry_run_ids(sweep));
}

// Starts the 24-configuration sweep below, sends `signal` once at least two records are
// durable, resumes, and checks every configuration is recorded exactly once, complete.
void interrupt_and_resume(const std::string& signal, const std::string& exit_status) {
  const Folder f = folder();
  // 24 configurations sharing one small reference, seconds in all even on a loaded machine:
  // the signal lands in the middle. Exactly 2 measured frames each (no time target): how
  // long a configuration measures is not what this tests.
  const std::string sweep = f.sweep("kill.json", R"({"axes": {"structures": ["psppsll", "ppfla", "psppfla"],
      "views": [4, 8, 12, 16], "r_ldm": [64, 128], "image_size": "32x32", "frames": 2, "warmup": 1},
      "settings": {"reference": {"spp": 64}, "timing": {"target": 0}}})");
  const fs::path out = f.dir / "run", log = f.dir / "log";
  const std::string command = std::string(LDM_BINARY_PATH) + " sweep " + sweep + f.cache() + " --out " + out.string();
  // Signalled once two records are durable, with later ones in flight.
  const std::string script =
      "(" + command + " > " + log.string() + " 2>&1 & pid=$!; "
      "for i in $(seq 600); do [ \"$(grep -c '\"record\"' " + (out / "records.jsonl").string() +
      " 2>/dev/null)\" -ge 2 ] && break; sleep 0.02; done; kill -" + signal + " $pid; wait $pid; echo \"exit=$?\")";
  std::string output;
  test::run_command(script, &output);
  ASSERT_NE(output.find("exit=" + exit_status), std::string::npos) << output << read_text(log);
  const size_t before = journal_records(out).size();
  ASSERT_GE(before, 2u);
  ASSERT_LT(before, 24u) << "the sweep finished before the signal";

  const Outcome resumed = ldmbench("sweep " + sweep + f.cache() + " --out " + out.string());
  EXPECT_EQ(resumed.status, 0) << resumed.output;
  EXPECT_NE(resumed.output.find("resuming: " + std::to_string(before)), std::string::npos) << resumed.output;
  // Every configuration exactly once, in sweep order, in the journal and both tables.
  const std::vector<std::string> expected = dry_run_ids(sweep);
  ASSERT_EQ(expected.size(), 24u);
  std::vector<std::string> journal_ids;
  for (const auto& r : journal_records(out)) journal_ids.push_back(r["config_id"]);
  EXPECT_EQ(journal_ids, expected);
  EXPECT_EQ(csv_ids(out), expected);
  const auto json = nlohmann::json::parse(read_text(out / "records.json"));
  ASSERT_EQ(json["records"].size(), 24u);
  for (const auto& r : json["records"]) {
    EXPECT_EQ(r["status"], "ok") << r["config_id"];
    EXPECT_TRUE(r.contains("mse")) << r["config_id"];  // complete rows: scored
    EXPECT_TRUE(fs::exists(out / r["image_png"].get<std::string>())) << r["config_id"];
  }
  // No orphan of the configuration in flight: every image is one a record names (or the EXR
  // or PNG beside it).
  std::set<std::string> referenced;
  for (const auto& r : json["records"])
    for (const char* key : {"image_exr", "image_png", "reference_exr", "ssim_map_png", "diff_png"})
      referenced.insert(fs::path(r[key].get<std::string>()).stem().string());
  for (const auto& entry : fs::directory_iterator(out / "images"))
    EXPECT_TRUE(referenced.count(entry.path().stem().string())) << "orphan " << entry.path();
}

TEST(SweepCli, SigkillMidSweepLosesAtMostTheConfigurationInFlight) { interrupt_and_resume("KILL", "137"); }

TEST(SweepCli, SigintMidSweepAbandonsTheConfigurationInFlight) { interrupt_and_resume("INT", "130"); }

TEST(SweepCli, ShardsMergeIntoTheWholeSweep) {
  const Folder f = folder();
  const std::string sweep = f.sweep("small.json", kSmall);
  std::vector<std::string> shards;
  for (int i = 0; i < 3; ++i) {
    const fs::path out = f.dir / ("shard" + std::to_string(i));
    const Outcome o = ldmbench("sweep " + sweep + " --shard " + std::to_string(i) + "/3 --out " + out.string());
    ASSERT_EQ(o.status, 0) << o.output;
    EXPECT_EQ(csv_ids(out).size(), 2u);
    shards.push_back(out.string());
  }
  const fs::path merged = f.dir / "merged";
  // Given in any order, the merge is ordered by shard index.
  const Outcome m = ldmbench("merge " + merged.string() + " " + shards[2] + " " + shards[0] + " " + shards[1]);
  ASSERT_EQ(m.status, 0) << m.output;
  std::vector<std::string> ids = csv_ids(merged), expected = dry_run_ids(sweep);
  EXPECT_EQ(std::set<std::string>(ids.begin(), ids.end()), std::set<std::string>(expected.begin(), expected.end()));
  EXPECT_EQ(ids.size(), expected.size());
  const auto json = nlohmann::json::parse(read_text(merged / "records.json"));
  EXPECT_EQ(json["records"].size(), 6u);
  EXPECT_EQ(json["run"]["sweep_configurations"], 6);
  for (const auto& r : json["records"])
    EXPECT_TRUE(fs::exists(merged / r["frame_samples_csv"].get<std::string>())) << r["config_id"];
  // The merged folder compares like any run.
  EXPECT_EQ(ldmbench("compare " + merged.string() + " " + merged.string() + " --fail-on memory,status").status, 0);

  // A missing shard is a warning; the same shard twice is a duplicate; OUT must be empty.
  const Outcome partial = ldmbench("merge " + (f.dir / "partial").string() + " " + shards[0] + " " + shards[1]);
  EXPECT_EQ(partial.status, 0) << partial.output;
  EXPECT_NE(partial.output.find("shard 2/3 is not among the runs"), std::string::npos) << partial.output;
  const Outcome twice = ldmbench("merge " + (f.dir / "twice").string() + " " + shards[0] + " " + shards[0]);
  EXPECT_EQ(twice.status, 2) << twice.output;
  EXPECT_NE(twice.output.find("is in both"), std::string::npos) << twice.output;
  EXPECT_FALSE(fs::exists(f.dir / "twice"));
  EXPECT_EQ(ldmbench("merge " + merged.string() + " " + shards[0]).status, 2);

  // A run of another device (or build, or sweep file) is refused unless allowed.
  const fs::path journal = fs::path(shards[1]) / "records.jsonl";
  std::string text = read_text(journal);
  const std::string device = "\"device\":\"";
  const size_t at = text.find(device);  // the run entry comes first
  ASSERT_NE(at, std::string::npos);
  text.insert(at + device.size(), "Other GPU ");
  std::ofstream(journal, std::ios::trunc) << text;
  const Outcome mismatch = ldmbench("merge " + (f.dir / "mismatch").string() + " " + shards[0] + " " + shards[1]);
  EXPECT_EQ(mismatch.status, 2) << mismatch.output;
  EXPECT_NE(mismatch.output.find("differ in device"), std::string::npos) << mismatch.output;
  EXPECT_FALSE(fs::exists(f.dir / "mismatch"));
  const Outcome allowed = ldmbench("merge --allow-mismatch " + (f.dir / "mismatch").string() + " " + shards[0] +
                                   " " + shards[1]);
  EXPECT_EQ(allowed.status, 0) << allowed.output;
  EXPECT_NE(allowed.output.find("warning"), std::string::npos) << allowed.output;
}

TEST(SweepCli, SlurmScriptRunsItsShardsAndMerges) {
  // The array task's and the merge job's branches of scripts/slurm-sweep.sh, as Slurm would
  // run them (the environment Slurm sets, no Slurm needed).
  const Folder f = folder();
  const std::string sweep = f.sweep("small.json", kSmall);
  const std::string script = std::string(LDM_TEST_SOURCE_DIR) + "/../scripts/slurm-sweep.sh";
  const std::string out = (f.dir / "slurm").string();
  const std::string env = "LDMBENCH=" + std::string(LDM_BINARY_PATH) + " ";
  std::string output;
  // The variables Slurm sets in an array task (job 101 of array 100, task i, on node n7
  // with GPU 3, which CUDA_VISIBLE_DEVICES makes the task's ordinal 0), and no others: the
  // records name them. An LDM_GPU from the submitting shell must not pick another GPU.
  for (int i = 0; i < 2; ++i)
    ASSERT_EQ(test::run_command(env + "SLURM_ARRAY_TASK_ID=" + std::to_string(i) + " SLURM_ARRAY_JOB_ID=100 " +
                                    "SLURM_JOB_ID=" + std::to_string(101 + i) + " SLURMD_NODENAME=n7 " +
                                    "SLURM_JOB_GPUS=3 CUDA_VISIBLE_DEVICES=3 LDM_GPU=5 " + script + " " + sweep +
                                    " 2 " + out, &output), 0)
        << output;
  ASSERT_EQ(test::run_command(env + "LDM_SLURM_MERGE=1 " + script + " " + sweep + " 2 " + out, &output), 0)
      << output;
  EXPECT_EQ(csv_ids(fs::path(out) / "shard-1").size(), 3u);
  std::vector<std::string> ids = csv_ids(fs::path(out) / "merged"), expected = dry_run_ids(sweep);
  std::sort(ids.begin(), ids.end());
  std::sort(expected.begin(), expected.end());
  EXPECT_EQ(ids, expected);
  const auto merged = nlohmann::json::parse(read_text(fs::path(out) / "merged" / "records.json"));
  std::set<std::string> tasks;
  for (const auto& r : merged["records"]) {
    EXPECT_FALSE(r["host"].get<std::string>().empty());
    EXPECT_EQ(r["slurm_array_job_id"], "100");
    EXPECT_EQ(r["slurm_node"], "n7");
    EXPECT_EQ(r["slurm_gpus"], "3");
    const std::string task = r["slurm_array_task_id"];
    EXPECT_EQ(r["slurm_job_id"], task == "0" ? "101" : "102");
    tasks.insert(task);
  }
  EXPECT_EQ(tasks, (std::set<std::string>{"0", "1"}));
  // Outside Slurm a record names its host only.
  const auto single = nlohmann::json::parse(read_text(fs::path(out) / "shard-0" / "records.json"));
  const Outcome plain = ldmbench("sweep " + sweep + " --out " + (f.dir / "plain").string());
  ASSERT_EQ(plain.status, 0) << plain.output;
  const auto plain_records = nlohmann::json::parse(read_text(f.dir / "plain" / "records.json"))["records"];
  EXPECT_EQ(plain_records[0]["host"], single["records"][0]["host"]);
  if (!std::getenv("SLURM_JOB_ID")) EXPECT_FALSE(plain_records[0].contains("slurm_job_id"));  // ctest not in a job
}

TEST(SweepCli, CiSmallSweepReproducesTheCommittedBaseline) {
  // sweeps/ci-small.json measures the configurations of results/baselines/ci-small (same ids,
  // same settings, through the same path as `ldmbench run`): memory, accuracy and status
  // agree with the committed records.
  const Folder f = folder();
  const std::string root = std::string(LDM_TEST_SOURCE_DIR) + "/..";
  const fs::path out = f.dir / "ci";
  const Outcome run = ldmbench("sweep " + root + "/sweeps/ci-small.json" + f.cache() + " --out " + out.string());
  ASSERT_EQ(run.status, 0) << run.output;
  const Outcome compared = ldmbench("compare " + root + "/results/baselines/ci-small " + out.string() +
                                    " --fail-on accuracy,memory,status");
  EXPECT_EQ(compared.status, 0) << compared.output;
  EXPECT_NE(compared.output.find("regressions: time"), std::string::npos) << compared.output;
  EXPECT_NE(compared.output.find("memory 0 accuracy 0 status 0"), std::string::npos) << compared.output;
}

TEST(SweepCli, RunRedoesFailedConfigurationsWhenAsked) {
  // `ldmbench run` shares the loop: --redo-failed resumes the same sweep (it is not part of
  // the sweep's identity) and measures the failed configuration again.
  const Folder f = folder();
  const int64_t block = test::gl_context().device().max_ssbo_block_bytes;
  const int too_big = int(std::ceil(std::sqrt(double(block) / 4.0 / 64))) + 1;
  const fs::path out = f.dir / "run";
  const std::string run = "run -N 64 -R " + std::to_string(too_big) +
                          ",16 --width 32 --height 32 --frames 1 --warmup 0 --time-target 0 --no-reference --no-images --out " +
                          out.string();
  ASSERT_EQ(ldmbench(run).status, 3);
  const Outcome redone = ldmbench(run + " --redo-failed");
  EXPECT_EQ(redone.status, 3) << redone.output;
  EXPECT_NE(redone.output.find("1 failed one(s) to redo"), std::string::npos) << redone.output;
  EXPECT_EQ(journal_records(out).size(), 3u);
  EXPECT_EQ(csv_ids(out).size(), 2u);
}

TEST(SweepCli, SlurmScriptSubmitsGpuOptionsAndNamedLogs) {
  // The login node's branch of scripts/slurm-sweep.sh with a stand-in sbatch on PATH that
  // logs its arguments (one line per call) and answers job ids 41, 42, ... (the real
  // cluster: scripts/slurm-ci.sh in CI).
  const Folder f = folder();
  const std::string sweep = f.sweep("small.json", kSmall);
  const fs::path bin = f.dir / "bin";
  fs::create_directories(bin);
  const fs::path calls = f.dir / "sbatch-calls";
  std::ofstream(bin / "sbatch") << "#!/bin/sh\necho \"$*\" >> '" << calls.string() << "'\n"
                                << "echo $((41 + $(wc -l < '" << calls.string() << "') - 1))\n";
  fs::permissions(bin / "sbatch", fs::perms::owner_all);
  const std::string script = std::string(LDM_TEST_SOURCE_DIR) + "/../scripts/slurm-sweep.sh";
  const std::string out = (f.dir / "slurm").string();
  const std::string env = "PATH=" + bin.string() + ":$PATH LDMBENCH=" + std::string(LDM_BINARY_PATH) + " ";
  auto submit = [&](const std::string& vars, std::string* output) {
    fs::remove(calls);
    return test::run_command(env + vars + " " + script + " " + sweep + " 3 " + out, output);
  };
  auto lines = [&] {
    std::istringstream in(read_text(calls));
    std::vector<std::string> out;
    for (std::string line; std::getline(in, line);) out.push_back(line);
    return out;
  };

  std::string output;
  ASSERT_EQ(submit("", &output), 0) << output;
  std::vector<std::string> call = lines();
  ASSERT_EQ(call.size(), 2u) << output;
  // The array: a GPU of its own (several tasks per node, one per GPU: no --exclusive);
  // every task's log names shard and job.
  EXPECT_NE(call[0].find("--gres=gpu:1 "), std::string::npos) << call[0];
  EXPECT_EQ(call[0].find("--exclusive"), std::string::npos) << call[0];
  EXPECT_NE(call[0].find("--array=0-2"), std::string::npos) << call[0];
  EXPECT_NE(call[0].find("--output=" + out + "/slurm-logs/ldmbench-shard-%a-of-3-job-%A_%a.out"), std::string::npos)
      << call[0];
  // The merge: after the array, no GPU, its own log.
  EXPECT_NE(call[1].find("--dependency=afterany:41"), std::string::npos) << call[1];
  EXPECT_EQ(call[1].find("--gres"), std::string::npos) << call[1];
  EXPECT_NE(call[1].find("--output=" + out + "/slurm-logs/ldmbench-merge-job-%j.out"), std::string::npos) << call[1];
  EXPECT_TRUE(fs::is_directory(fs::path(out) / "slurm-logs"));
  EXPECT_NE(output.find("array job 41"), std::string::npos) << output;
  EXPECT_NE(output.find("merge job 42"), std::string::npos) << output;

  // No GPU (the CI's node); one task resubmitted; the site's own GPU options.
  ASSERT_EQ(submit("LDM_SLURM_GPUS=0 LDM_SLURM_TASKS=1", &output), 0) << output;
  call = lines();
  ASSERT_EQ(call.size(), 2u);
  EXPECT_EQ(call[0].find("--gres"), std::string::npos) << call[0];
  EXPECT_EQ(call[0].find("--exclusive"), std::string::npos) << call[0];
  EXPECT_NE(call[0].find("--array=1 "), std::string::npos) << call[0];
  ASSERT_EQ(submit("LDM_SLURM_GPU_ARGS=--gres=gpu:a100:1", &output), 0) << output;
  EXPECT_NE(lines()[0].find("--gres=gpu:a100:1 "), std::string::npos);

  // Refused before anything is queued: a bad switch, a bad sweep.
  EXPECT_EQ(submit("LDM_SLURM_GPUS=yes", &output), 2) << output;
  EXPECT_NE(output.find("LDM_SLURM_GPUS must be 1 or 0"), std::string::npos) << output;
  EXPECT_FALSE(fs::exists(calls));
  std::string broken = kSmall;
  broken.replace(broken.find("\"psppfla\""), 9, "\"foo\"");
  const std::string bad = f.sweep("bad.json", broken);
  EXPECT_NE(test::run_command(env + script + " " + bad + " 3 " + out, &output), 0);
  EXPECT_NE(output.find("unknown structure \"foo\""), std::string::npos) << output;
  EXPECT_FALSE(fs::exists(calls));
}

}  // namespace
}  // namespace ldm
