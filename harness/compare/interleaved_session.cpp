#include "harness/compare/interleaved_session.h"

#include <unistd.h>

#include <chrono>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <ostream>
#include <set>
#include <sstream>

#include <nlohmann/json.hpp>

#include "harness/run/run_command.h"
#include "harness/compare/run_comparison.h"
#include "harness/util/error.h"
#include "harness/util/files.h"
#include "harness/util/interrupt.h"
#include "harness/util/process.h"

namespace ldm {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

constexpr const char* kSessionFile = "session.json";

// Options the session sets in every child; the command may not set them itself.
const std::set<std::string>& session_options() {
  static const std::set<std::string> names = {"--out", "--repetitions", "--step", "--interleaved-session",
                                              "--overwrite", "--dry-run", "--isolation", "--shard"};
  return names;
}

std::vector<std::string> concatenated(std::vector<std::string> a, const std::vector<std::string>& b) {
  a.insert(a.end(), b.begin(), b.end());
  return a;
}

void check_command_head(const std::vector<std::string>& command) {
  if (command.empty() || (command.front() != "run" && command.front() != "sweep"))
    throw UserError("interleave: expected `-- run ...` or `-- sweep FILE ...` after the binaries");
}

// No option the session sets itself.
void check_command(const std::vector<std::string>& command) {
  for (const std::string& a : command) {
    const std::string name = a.substr(0, a.find('='));
    if (session_options().count(name))
      throw UserError("interleave: " + name + " is the session's (it sets --out, --repetitions, "
                      "--step and --interleaved-session in every child); leave it out of the command");
  }
}

void check_binary(const std::string& binary, const char* which) {
  std::error_code error;
  if (!fs::is_regular_file(binary, error) || ::access(binary.c_str(), X_OK) != 0)
    throw UserError("interleave: " + std::string(which) + " '" + binary + "' is not an executable file");
}

std::vector<std::string> planned_ids(const std::string& binary, const std::vector<std::string>& command) {
  std::vector<std::string> argv = {binary};
  argv.insert(argv.end(), command.begin(), command.end());
  argv.push_back("--dry-run");
  const ProcessResult result = run_process(argv, true);
  if (!result.started || result.status != 0)
    throw UserError("interleave: '" + binary + "' could not list the configurations (exit " +
                    std::to_string(result.status) + "; an ldmbench build with --dry-run and --step " +
                    "is needed):\n" + result.output);
  const std::vector<std::string> ids = listed_configuration_ids(result.output);
  if (ids.empty()) throw UserError("interleave: '" + binary + "' lists no configuration:\n" + result.output);
  return ids;
}

std::string session_name() {
  const std::time_t now = std::time(nullptr);
  std::tm local{};
  localtime_r(&now, &local);
  std::ostringstream out;
  out << std::put_time(&local, "%Y%m%d-%H%M%S") << "-" << ::getpid();
  return out.str();
}

// A fresh session, or the one an earlier call of the same command left (resumed).
std::string open_session(const InterleavedSession& s) {
  const fs::path dir(s.out_dir), file = dir / kSessionFile;
  const json identity = {{"binary_a", fs::absolute(s.binary_a).string()},
                         {"binary_b", fs::absolute(s.binary_b).string()},
                         {"command", s.command},
                         {"a_arguments", s.a_arguments},
                         {"b_arguments", s.b_arguments},
                         {"ignored_params", s.ignored_params},
                         {"repetitions", s.repetitions}};
  std::error_code error;
  if (fs::exists(file, error)) {
    json previous;
    try {
      std::ifstream in(file);
      previous = json::parse(in);
    } catch (const json::exception& e) {
      throw UserError(file.string() + ": not a session file (" + e.what() + ")");
    }
    for (const auto& [key, value] : identity.items())
      if (previous.value(key, json()) != value)
        throw UserError("interleave: '" + s.out_dir + "' holds another session (its " + key +
                        " differs); choose another --out");
    return previous.value("session", std::string());
  }
  if (fs::exists(dir, error) && !fs::is_empty(dir, error))
    throw UserError("interleave: --out '" + s.out_dir + "' exists and holds no session; choose a new folder");
  fs::create_directories(dir, error);
  if (error) throw UserError("interleave: cannot create '" + s.out_dir + "': " + error.message());
  json state = identity;
  state["session"] = session_name();
  write_text_atomically(file.string(), state.dump(2) + "\n");
  return state["session"];
}

// What a child's progress line says after "<id> ... " (status and times), or its last line.
std::string outcome_of(const std::string& output) {
  std::istringstream lines(output);
  std::string last;
  for (std::string line; std::getline(lines, line);) {
    const size_t dots = line.find(" ... ");
    if (dots != std::string::npos) return line.substr(dots + 5);
    if (!line.empty()) last = line;
  }
  return last;
}

}  // namespace

std::vector<std::string> listed_configuration_ids(const std::string& listing) {
  std::vector<std::string> ids;
  std::istringstream lines(listing);
  for (std::string line; std::getline(lines, line);) {
    const size_t tab = line.find('\t');
    if (tab == std::string::npos || line.find_first_not_of("0123456789") != tab) continue;
    const size_t next = line.find('\t', tab + 1);
    ids.push_back(line.substr(tab + 1, next == std::string::npos ? std::string::npos : next - tab - 1));
  }
  return ids;
}

int run_interleaved_session(const InterleavedSession& s, std::ostream& log) {
  check_binary(s.binary_a, "A");
  check_binary(s.binary_b, "B");
  check_command_head(s.command);
  check_command(s.command);
  if (s.repetitions < 2) throw UserError("interleave: --repetitions must be at least 2 (pairs to test)");
  check_command(s.a_arguments);
  check_command(s.b_arguments);
  const std::vector<std::string> commands[2] = {concatenated(s.command, s.a_arguments), concatenated(s.command, s.b_arguments)};
  const std::vector<std::string> plans[2] = {planned_ids(s.binary_a, commands[0]),
                                             planned_ids(s.binary_b, commands[1])};
  const std::vector<std::string>& ids = plans[0];
  if (plans[0].size() != plans[1].size() || (s.ignored_params.empty() && plans[0] != plans[1]))
    throw UserError("interleave: A and B plan different configurations for this command (" +
                    std::to_string(plans[0].size()) + " and " + std::to_string(plans[1].size()) +
                    "; two variants pair in order only when --ignore-param names what differs)");
  const std::string session = open_session(s);
  install_stop_handlers();

  const fs::path dir(s.out_dir);
  const std::string folders[2] = {(dir / "a").string(), (dir / "b").string()};
  const std::string binaries[2] = {s.binary_a, s.binary_b};
  const size_t k = size_t(s.repetitions);
  log << "interleave: session " << session << ", " << ids.size() << " configurations x " << k
      << " repetitions x 2 builds, each repetition a process\n";
  int interrupted = 0;
  for (size_t round = 0; round < k && !interrupted; ++round) {
    for (size_t i = 0; i < ids.size() && !interrupted; ++i) {
      // ABBA over the configurations and rounds: neither build always goes first.
      const bool b_first = (round + i) % 2 == 1;
      std::string line = "[" + std::to_string(round + 1) + "/" + std::to_string(k) + "] [" +
                         std::to_string(i + 1) + "/" + std::to_string(ids.size()) + "] " + ids[i];
      for (int turn = 0; turn < 2 && !interrupted; ++turn) {
        const int side = b_first ? 1 - turn : turn;
        if (recorded_repetitions(folders[side], k)[plans[side][i]] > round) continue;  // resumed
        if ((interrupted = stop_signal())) break;
        std::vector<std::string> argv = {binaries[side]};
        argv.insert(argv.end(), commands[side].begin(), commands[side].end());
        for (const std::string& a : {std::string("--out"), folders[side], std::string("--repetitions"),
                                     std::to_string(k), std::string("--step"), plans[side][i],
                                     std::string("--interleaved-session"), session})
          argv.push_back(a);
        const ProcessResult result = run_process(argv, true, true);
        if (!result.started) throw UserError("interleave: cannot start " + binaries[side] + ": " + result.output);
        if (result.status > kExitInterruptedBase) {
          interrupted = result.status - kExitInterruptedBase;
        } else if (result.status != kExitOk && result.status != kExitSomeFailed) {
          log << result.output;
          log << "interleave: build " << (side ? "B" : "A") << " exited " << result.status << " on " << ids[i] << "\n";
          return kExitFailure;
        }
        line += std::string(side ? "  B: " : "  A: ") + outcome_of(result.output);
      }
      log << line << "\n" << std::flush;
    }
  }
  if (interrupted || (interrupted = stop_signal())) {
    log << "interleave: interrupted by signal " << interrupted << "; run the same command again to go on\n";
    return kExitInterruptedBase + interrupted;
  }
  const RunRecords a = load_run_records(folders[0]), b = load_run_records(folders[1]);
  CompareThresholds thresholds;
  thresholds.ignored_params = s.ignored_params;
  const RunComparison comparison = compare_runs(a, b, thresholds);
  write_text_atomically((dir / "comparison.json").string(), comparison_json(comparison, thresholds).dump(2) + "\n");
  log << comparison_table(comparison);
  std::string again = "ldmbench compare " + folders[0] + " " + folders[1];
  for (const auto& p : s.ignored_params) again += " --ignore-param " + p;
  log << "comparison: " << (dir / "comparison.json").string() << " (again: " << again << ")\n";
  return kExitOk;
}

}  // namespace ldm
