// The write path under injected faults (issue 19, "How to prove it"): a shim preloaded into
// ldmbench (shim/fault_shim.cpp) fails the k-th call that writes into the run folder (open
// for writing, write, fwrite, fclose, fsync, ftruncate, rename, mkdir, ...) with ENOSPC, for
// every k of a small sweep. After each fault the run must stop with the I/O exit status and
// the errno, leaving the folder in a consistent state on the way (the journal's records a
// prefix of the sweep, the tables what the journal gives, every named file whole, no orphan
// or temporary); the same command then completes it, every configuration exactly once.
// A disk that stays full (every call from the k-th on fails) is tried the same way.
#include <gtest/gtest.h>

#include <iostream>

#include "reliability_support.h"

namespace ldm::reliability {
namespace {

using test::Outcome;

Outcome with_faults(const std::string& args, const fs::path& dir, long at, bool sticky, const fs::path& log = {}) {
  std::string environment = std::string("LD_PRELOAD=") + LDM_FAULT_SHIM + " LDM_FAULT_DIR=" + dir.string() +
                            " LDM_FAULT_AT=" + std::to_string(at);
  if (sticky) environment += " LDM_FAULT_STICKY=1";
  if (!log.empty()) environment += " LDM_FAULT_LOG=" + log.string();
  return test::ldmbench(args, environment);
}

std::vector<std::string> log_lines(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

struct Figures {
  size_t points = 0, faults = 0, refused = 0, resumed = 0, lost = 0, doubled = 0;
  std::map<std::string, size_t> calls;  // injection points by call
  std::vector<std::string> failures;
};

// Every injection point of `sweep` (an `ldmbench run` command without --out) faulted once.
Figures fault_every_call(const std::string& sweep, bool sticky) {
  Figures f;
  const fs::path dir = test::make_temp_dir("ldm-faults");
  const fs::path log = dir / "calls.log";
  const Outcome clean = with_faults(sweep + " --out " + (dir / "clean" / "out").string(), dir / "clean", 0, false, log);
  EXPECT_EQ(clean.status, 0) << clean.output;
  const std::vector<std::string> calls = log_lines(test::read_text(log.string()));
  const FolderState reference = inspect_folder(dir / "clean" / "out");
  EXPECT_TRUE(reference.problems.empty()) << joined(reference.problems);
  f.points = calls.size();
  for (const auto& line : calls) {
    std::istringstream words(line);
    std::string k, call;
    words >> k >> call;
    ++f.calls[call];
  }
  for (size_t k = 1; k <= calls.size(); ++k) {
    const fs::path case_dir = dir / ("k" + std::to_string(k));
    const fs::path out = case_dir / "out";
    const std::string where = "fault at call " + calls[k - 1] + (sticky ? " (and every later one)" : "");
    const Outcome faulted = with_faults(sweep + " --out " + out.string(), case_dir, long(k), sticky);
    ++f.faults;
    if (faulted.status == 4 && faulted.output.find("No space left on device (ENOSPC)") != std::string::npos)
      ++f.refused;
    else
      f.failures.push_back(where + ": exit " + std::to_string(faulted.status) + " without the ENOSPC message\n" + faulted.output);
    // On the way: a consistent folder whose records are a prefix of the sweep's.
    const FolderState after = inspect_folder(out);
    for (const auto& problem : after.problems) f.failures.push_back(where + ": " + problem + "\n" + faulted.output);
    const bool prefix = after.ids.size() <= reference.ids.size() &&
                        std::equal(after.ids.begin(), after.ids.end(), reference.ids.begin());
    if (!prefix) f.failures.push_back(where + ": the records are not a prefix of the sweep's");
    // The same command, on a disk with room again, completes it.
    const Outcome resumed = test::ldmbench(sweep + " --out " + out.string());
    const FolderState done = inspect_folder(out);
    if (resumed.status == 0 && done.problems.empty() && done.ids == reference.ids) ++f.resumed;
    else f.failures.push_back(where + ": the resume ended " + std::to_string(resumed.status) + joined(done.problems) + "\n" + resumed.output);
    for (const auto& id : reference.ids) {
      const size_t n = done.journaled.count(id) ? done.journaled.at(id) : 0;
      f.lost += n == 0;
      f.doubled += n > 1;
    }
    std::error_code ignored;
    fs::remove_all(case_dir, ignored);
  }
  return f;
}

void report(const std::string& name, const Figures& f) {
  std::cout << "fault injection, " << name << ": " << f.points << " injection points (";
  bool first = true;
  for (const auto& [call, n] : f.calls) std::cout << (first ? "" : ", ") << n << " " << call, first = false;
  std::cout << "), " << f.faults << " faults injected, " << f.refused << " stopped with exit 4 and the errno, "
            << f.resumed << " resumed to the whole sweep, " << f.lost << " configurations lost, " << f.doubled
            << " doubled\n";
  EXPECT_GT(f.points, 20u);
  EXPECT_EQ(f.refused, f.faults);
  EXPECT_EQ(f.resumed, f.faults);
  EXPECT_EQ(f.lost, 0u);
  EXPECT_EQ(f.doubled, 0u);
  for (size_t i = 0; i < f.failures.size() && i < 10; ++i) ADD_FAILURE() << f.failures[i];
}

// Two configurations with images: the lock, the journal's run entry, each configuration's
// EXR and PNG and samples file, its journal line, both tables.
const std::string kSweep = "run -N 2,3" + kTiny;

TEST(ReliabilityFaults, EveryWriteOfASmallSweepFailsOnceAndNothingIsLost) {
  report("one fault", fault_every_call(kSweep, false));
}

TEST(ReliabilityFaults, ADiskThatStaysFullLosesNothingEither) {
  report("the disk stays full", fault_every_call(kSweep, true));
}

TEST(ReliabilityFaults, RepetitionsAreJournaledAndCombinedUnderFaults) {
  // One configuration measured twice: each repetition journaled with its samples, then the
  // combined record and samples file.
  report("repetitions", fault_every_call("run -N 2 --repetitions 2" + kTiny + "--no-images", false));
}

}  // namespace
}  // namespace ldm::reliability
