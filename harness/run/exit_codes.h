#pragma once
// The exit statuses of every ldmbench command (docs/guide/reliability.md lists them): in their
// own header, so that a command that only returns them need not include the run loop.

namespace ldm {

// Exit codes of `ldmbench run` (and of the other commands where they apply).
constexpr int kExitOk = 0;              // every configuration measured (ok or lossy)
constexpr int kExitUsage = 2;           // bad options or input: nothing was run or written
constexpr int kExitSomeFailed = 3;      // the sweep finished; some records are failed/invalid
constexpr int kExitFailure = 1;         // an error that is not the input's (a child process died, ...)
// Reading or writing a file failed (a full disk, a read-only folder: util/error.h IoError).
// The run stopped; the configuration in flight left nothing, what is recorded is consistent,
// and the same command resumes once the cause is fixed.
constexpr int kExitIoError = 4;
// The --out folder is held by another ldmbench (records/run_lock.h); nothing was done.
constexpr int kExitBusy = 5;
// Stopped by SIGINT or SIGTERM: 128 + the signal (130, 143), as a shell reports a process
// killed by it. Every finished configuration is recorded; the one in flight was abandoned
// (no record, no images); the same command resumes.
constexpr int kExitInterruptedBase = 128;

}  // namespace ldm
