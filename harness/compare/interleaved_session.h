#pragma once
// `ldmbench interleave A B -- COMMAND...`: two builds (or two binaries) measured alternately
// on one sweep in one session, the way hyperfine and Chromium's Pinpoint compare commands:
// for each round of repetitions and each configuration, build A's repetition and build B's
// are measured one right after the other (in ABBA order over the configurations, so that
// neither always goes first), each in a process of its own:
//   <binary> COMMAND... --out DIR/a|b --repetitions K --step ID --interleaved-session S
// Drift and the machine's load then hit both builds of a pair alike, and `ldmbench compare`
// of DIR/a and DIR/b (which the session prints at the end) pairs repetition j of A with
// repetition j of B (harness/stats/time_tests.h: paired_log_t). On a shared machine this is
// the only trustworthy time verdict; two runs an hour apart compare their load as much as
// their builds.
//
// Both binaries must be ldmbench builds that know --step (this one and later). Each is asked
// for its configurations first (--dry-run): the session refuses two builds that plan
// different ones (unless the difference is one --ignore-param leaves out, for two variants
// given by --a-args / --b-args). A killed session resumes with the same command.
#include <iosfwd>
#include <set>
#include <string>
#include <vector>

namespace ldm {

struct InterleavedSession {
  std::string binary_a, binary_b;
  std::vector<std::string> command;  // "run ..." or "sweep FILE ..."
  // Arguments only one side's command gets: two variants of one build (a slower
  // configuration, another shader variant) measured the same way. Their configurations pair
  // in order; their ids may then differ in what `ignored_params` leaves out of the identity.
  std::vector<std::string> a_arguments, b_arguments;
  std::set<std::string> ignored_params;
  std::string out_dir;               // holds a/, b/, session.json, comparison.json
  int repetitions = 5;
};

// Runs the session and prints the comparison; returns the exit status (kExit*). Throws
// UserError for bad input (binaries, command, folder), found before anything is measured.
int run_interleaved_session(const InterleavedSession& session, std::ostream& log);

// The configuration ids of a --dry-run listing ("index<TAB>id<TAB>..." lines).
std::vector<std::string> listed_configuration_ids(const std::string& listing);

}  // namespace ldm
