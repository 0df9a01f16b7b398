// One writer per run folder (issue 19, item 1; harness/records/run_lock.h): commands started
// together into one --out used to both measure, journaling 24 records for 12
// configurations; now exactly one measures and the others refuse, naming it. A lock left by
// a SIGKILLed process is taken over. And the --out values that said the wrong thing.
#include <gtest/gtest.h>

#include <regex>

#include "reliability_support.h"

namespace ldm::reliability {
namespace {

using test::Outcome;

struct Finished {
  int status;
  std::string log;
  long pid;
};

// Starts `commands` together (each in the background of one shell) and waits for all.
std::vector<Finished> start_together(const fs::path& dir, const std::vector<std::string>& commands) {
  std::string script;
  for (size_t i = 0; i < commands.size(); ++i) {
    const std::string n = std::to_string(i);
    script += "( " + commands[i] + " > " + (dir / ("log" + n)).string() + " 2>&1 & echo $! > " +
              (dir / ("pid" + n)).string() + "; wait $!; echo $? > " + (dir / ("status" + n)).string() + " ) & ";
  }
  script += "wait";
  std::string ignored;
  test::run_command(script, &ignored);
  std::vector<Finished> out;
  for (size_t i = 0; i < commands.size(); ++i) {
    const std::string n = std::to_string(i);
    out.push_back({std::stoi(test::read_text((dir / ("status" + n)).string())), test::read_text((dir / ("log" + n)).string()),
                   std::stol(test::read_text((dir / ("pid" + n)).string()))});
  }
  return out;
}

TEST(ReliabilityLock, OneSweepStartedFourTimesIsMeasuredOnce) {
  const fs::path dir = test::make_temp_dir("ldm-lock");
  const fs::path out = dir / "run";
  const std::string command = std::string(LDM_BINARY_PATH) + " run -N 2,3,4" + kTiny + "--out " + out.string();
  const auto runs = start_together(dir, {command, command, command, command});
  // Exactly one measured; the others were refused while it held the folder (busy, naming
  // it), or, starting after it ended, found every configuration recorded and measured nothing.
  size_t measured = 0, refused = 0;
  long holder = 0;
  std::string logs;
  for (const auto& r : runs) {
    logs += r.log + "\n";
    if (r.status == 0 && r.log.find("[1/3]") != std::string::npos) ++measured, holder = r.pid;
  }
  ASSERT_EQ(measured, 1u) << logs;
  for (const auto& r : runs) {
    if (r.pid == holder) continue;
    if (r.status == 0) {
      EXPECT_NE(r.log.find("resuming: 3"), std::string::npos) << r.log;
      continue;
    }
    ++refused;
    EXPECT_EQ(r.status, 5) << r.log;
    EXPECT_NE(r.log.find("is in use by PID " + std::to_string(holder)), std::string::npos) << r.log;
    EXPECT_NE(r.log.find("ldmbench run -N 2,3,4"), std::string::npos) << r.log;
  }
  EXPECT_GE(refused, 1u) << "no command met the lock: the test proves nothing\n" << logs;
  // Every configuration journaled exactly once (before: twice or more), tables agreeing.
  const FolderState state = inspect_folder(out);
  EXPECT_TRUE(state.problems.empty()) << joined(state.problems);
  ASSERT_EQ(state.ids.size(), 3u);
  for (const auto& [id, count] : state.journaled) EXPECT_EQ(count, 1u) << id;
  EXPECT_FALSE(fs::exists(out / ".ldmbench.lock"));
}

TEST(ReliabilityLock, TwoDifferentRunsIntoOneFolderNeverMix) {
  const fs::path dir = test::make_temp_dir("ldm-lock");
  const fs::path out = dir / "run";
  const std::string a = std::string(LDM_BINARY_PATH) + " run -N 2,3,4" + kTiny + "--out " + out.string();
  const std::string b = std::string(LDM_BINARY_PATH) + " run -N 5,6,7" + kTiny + "--out " + out.string();
  const auto runs = start_together(dir, {a, b});
  // One measured; the other was refused while it did (busy), or after (another sweep).
  ASSERT_EQ((runs[0].status == 0) + (runs[1].status == 0), 1) << runs[0].log << runs[1].log;
  const Finished& refused = runs[0].status == 0 ? runs[1] : runs[0];
  EXPECT_TRUE(refused.status == 5 || refused.status == 2) << refused.log;
  const FolderState state = inspect_folder(out);
  EXPECT_TRUE(state.problems.empty()) << joined(state.problems);
  ASSERT_EQ(state.ids.size(), 3u);
  const std::string views = runs[0].status == 0 ? "-n2-" : "-n5-";
  EXPECT_NE(state.ids[0].find(views), std::string::npos) << state.ids[0];
  // The refused command, run again, does not adopt the other's records: another sweep.
  const Outcome again = test::run_shell(runs[0].status == 0 ? b : a);
  EXPECT_EQ(again.status, 2) << again.output;
  EXPECT_NE(again.output.find("different sweep"), std::string::npos) << again.output;
}

TEST(ReliabilityLock, AStaleLockOfAKilledRunIsTakenOver) {
  const fs::path dir = test::make_temp_dir("ldm-lock");
  const fs::path out = dir / "run", log = dir / "log";
  const std::string command = std::string(LDM_BINARY_PATH) + " run -N 2,3,4,5,6,7,8" + kTiny + "--out " + out.string();
  // SIGKILLed once its first record is durable: the lock file stays, naming a dead PID.
  const std::string script = "(" + command + " > " + log.string() + " 2>&1 & pid=$!; echo $pid > " +
                             (dir / "pid").string() + "; for i in $(seq 600); do grep -q '\"record\"' " +
                             (out / "records.jsonl").string() + " 2>/dev/null && break; sleep 0.02; done; kill -KILL $pid; "
                             "wait $pid; echo \"exit=$?\")";
  std::string output;
  test::run_command(script, &output);
  ASSERT_NE(output.find("exit=137"), std::string::npos) << output << test::read_text(log.string());
  const std::string dead = test::read_text((dir / "pid").string());
  const std::string stale = test::read_text((out / ".ldmbench.lock").string());
  ASSERT_NE(stale.find("pid " + dead.substr(0, dead.find('\n'))), std::string::npos) << stale;
  // The same command takes the folder over, says whose lock it was, and finishes the sweep.
  const Outcome resumed = test::run_shell(command);
  EXPECT_EQ(resumed.status, 0) << resumed.output;
  EXPECT_NE(resumed.output.find("taking over the lock of PID " + dead.substr(0, dead.find('\n'))), std::string::npos)
      << resumed.output;
  const FolderState state = inspect_folder(out);
  EXPECT_TRUE(state.problems.empty()) << joined(state.problems);
  EXPECT_EQ(state.ids.size(), 7u);
  EXPECT_FALSE(fs::exists(out / ".ldmbench.lock"));
}

TEST(ReliabilityLock, MergeLocksItsOutputToo) {
  const fs::path dir = test::make_temp_dir("ldm-lock");
  const fs::path run = dir / "run", merged = dir / "merged";
  ASSERT_EQ(test::ldmbench("run -N 2" + kTiny + "--out " + run.string()).status, 0);
  // A live process holding the merged folder: a shell that keeps the flock while its
  // child (not ldmbench's parent) merges into it.
  fs::create_directories(merged);
  const std::string script = write_file(
      dir / "hold.sh", "exec 9> " + (merged / ".ldmbench.lock").string() +
                           "\nflock -n 9\nprintf 'pid %d\\ncommand holder\\n' $$ >&9\n( " + LDM_BINARY_PATH +
                           " merge " + merged.string() + " " + run.string() + " )\n");
  const Outcome o = test::run_shell("bash " + script);
  EXPECT_EQ(o.status, 5) << o.output;
  EXPECT_NE(o.output.find("in use by PID"), std::string::npos) << o.output;
  EXPECT_FALSE(fs::exists(merged / "records.jsonl"));
}

TEST(ReliabilityLock, OutValuesThatSaidTheWrongThing) {
  const fs::path dir = test::make_temp_dir("ldm-lock");
  // A dangling symbolic link said "File exists".
  fs::create_symlink(dir / "nowhere", dir / "link");
  Outcome o = test::ldmbench("run -N 2" + kTiny + "--out " + (dir / "link").string());
  EXPECT_EQ(o.status, 2) << o.output;
  EXPECT_NE(o.output.find("symbolic link"), std::string::npos) << o.output;
  EXPECT_NE(o.output.find("does not exist"), std::string::npos) << o.output;
  EXPECT_FALSE(fs::exists(dir / "nowhere"));
  // An empty --out wrote under results/runs/<timestamp> without a word.
  o = test::run_shell("cd " + dir.string() + " && " + LDM_BINARY_PATH + " run -N 2" + kTiny + "--out ''");
  EXPECT_EQ(o.status, 2) << o.output;
  EXPECT_NE(o.output.find("--out \"\": an empty path"), std::string::npos) << o.output;
  EXPECT_FALSE(fs::exists(dir / "results"));
  o = test::run_shell("cd " + dir.string() + " && " + LDM_BINARY_PATH + " sweep x.json --out=");
  EXPECT_EQ(o.status, 2) << o.output;
  EXPECT_NE(o.output.find("an empty path"), std::string::npos) << o.output;
}

}  // namespace
}  // namespace ldm::reliability
