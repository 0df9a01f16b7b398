#pragma once
// Running third-party code that may crash, hang or exhaust memory on hostile input (Assimp's
// importers on a malformed file) in a child process, so that the caller sees an outcome it
// can report instead of dying with the child.
//
// The child is a fork() of this process: it runs `work`, writes the bytes it returns to a
// pipe and ends with _exit (no destructors, atexit handlers or stdio flushes of the parent's
// state run twice). fork() copies only the calling thread, so `work` must not wait on
// anything another thread holds: malloc and stdio are safe in glibc's child after fork (glibc
// resets their locks); a GL context, TBB or Embree are not, and `work` must not touch them.
#include <functional>
#include <string>

namespace ldm {

// Exit status of a child whose sanitizer (where one is linked) reported an error in the work,
// a failed allocation included: a Crashed outcome with this exit_status.
inline constexpr int kSanitizerDeathStatus = 97;

struct IsolatedOutcome {
  enum class Kind {
    Returned,   // `work` returned: `bytes` holds its result
    Threw,      // `work` threw: `message` holds what()
    Crashed,    // the child died of a signal (`signal`) or exited without a result
    TimedOut,   // the child ran past the time limit and was killed
    NotStarted  // fork() or pipe() failed (`message` says why)
  };
  Kind kind = Kind::NotStarted;
  std::string bytes;
  std::string message;
  int signal = 0;       // Crashed by a signal: its number
  int exit_status = 0;  // Crashed without a signal: the child's exit status
};

struct IsolationLimits {
  double seconds = 600;  // wall-clock limit for the child
  // Address-space limit of the child (RLIMIT_AS), so that a file that makes the importer
  // allocate without bound fails in the child instead of exhausting the machine. 0: none.
  // Under AddressSanitizer, whose shadow takes terabytes of address space, a cap is only
  // meaningful above what the process has mapped already (mesh_import.cpp measures it).
  unsigned long long address_space_bytes = 0;
};

// Runs `work` in a child process and waits for it (at most `limits.seconds`). The child's
// stdout and stderr are discarded (a third-party library's chatter must not interleave with
// ldmbench's output); a crash is reported as Crashed with the signal.
IsolatedOutcome run_isolated(const std::function<std::string()>& work, const IsolationLimits& limits);

// "SIGSEGV (segmentation fault)" for a signal number.
std::string describe_signal(int signal);

}  // namespace ldm
