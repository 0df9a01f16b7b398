#pragma once
// Running another program (the report's Python script) without a shell, so that no argument
// is ever re-parsed: argv[0] is looked up on PATH unless it holds a '/'.
#include <string>
#include <vector>

namespace ldm {

struct ProcessResult {
  bool started = false;  // false: the program could not be run (output says why)
  int status = -1;       // its exit status, or 128 + the signal that ended it
  std::string output;    // stdout and stderr together, when captured
};

// Runs argv and waits for it. With `capture` its stdout and stderr are collected into
// `output`; without, it writes to this process's own streams. With `forward_stop`, a
// SIGINT or SIGTERM this process receives while waiting (harness/util/interrupt.h) is sent
// on to the child, which then stops as it would on its own.
ProcessResult run_process(const std::vector<std::string>& argv, bool capture, bool forward_stop = false);

// Wall seconds since this process started (since its static initialisation: exec and
// dynamic loading are not counted, a few milliseconds).
double seconds_since_process_start();

// The absolute path of the running executable (/proc/self/exe), or "" when unknown.
std::string executable_path();

}  // namespace ldm
