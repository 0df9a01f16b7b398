#pragma once
#include <iosfwd>
#include <string>

#include "harness/app/run_settings.h"

namespace ldm {

// Exit codes of `ldmbench run`.
constexpr int kExitOk = 0;              // every configuration measured (ok or lossy)
constexpr int kExitUsage = 2;           // bad options or input: nothing was run or written
constexpr int kExitSomeFailed = 3;      // the sweep finished; some records are failed/invalid

// Runs the sweep: validates every axis value and loads every scene before touching the GPU
// (so bad input writes nothing), then measures each configuration, rewriting records.csv and
// records.json after each one. A configuration that throws becomes a "failed" record and the
// sweep goes on. `command_line` is stored in the run metadata.
int run_benchmark(const RunSettings& settings, const std::string& command_line, std::ostream& log);

}  // namespace ldm
