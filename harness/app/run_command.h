#pragma once
#include <iosfwd>
#include <string>

#include "harness/app/run_settings.h"

namespace ldm {

// Exit codes of `ldmbench run`.
constexpr int kExitOk = 0;              // every configuration measured (ok or lossy)
constexpr int kExitUsage = 2;           // bad options or input: nothing was run or written
constexpr int kExitSomeFailed = 3;      // the sweep finished; some records are failed/invalid
// Stopped by SIGINT or SIGTERM: 128 + the signal (130, 143), as a shell reports a process
// killed by it. Every finished configuration is recorded; the one in flight was abandoned
// (no record, no images); the same command resumes.
constexpr int kExitInterruptedBase = 128;

// Runs the sweep: validates every axis value, loads every scene and checks --out and
// --cache-dir before touching the GPU (so bad input writes nothing), then measures each
// configuration: its record is appended to records.jsonl (fsync'd), and records.csv and
// records.json are re-derived from the records. A configuration that throws becomes a
// "failed" record and the sweep goes on. An --out folder holding the same sweep resumes it
// (records/run_folder.h). `command_line` is stored in the run metadata.
int run_benchmark(const RunSettings& settings, const std::string& command_line, std::ostream& log);

// The checks run_benchmark makes on every axis value before any GPU work (structures and
// passes with their parameters, --param owners, the budget option); throws UserError.
// Shared with `ldmbench view`.
void validate_axes(const RunSettings& settings);

}  // namespace ldm
