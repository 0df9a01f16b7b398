#include "harness/util/isolated_call.h"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstring>
#include <exception>

// Set where a sanitizer runtime is linked (the fuzzers, scripts/sanitize.sh): it runs
// instead of the sanitizer's own death callbacks when the child dies of a report, so that a
// fuzzer's callback (which would save the input as a crash of the fuzzer) never runs there.
extern "C" void __sanitizer_set_death_callback(void (*callback)(void)) __attribute__((weak));

namespace ldm {
namespace {

constexpr char kReturned = 'R', kThrew = 'T';

void die_of_sanitizer_report() { _exit(kSanitizerDeathStatus); }

bool write_all(int fd, const char* data, size_t size) {
  while (size > 0) {
    const ssize_t n = write(fd, data, size);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    data += n;
    size -= size_t(n);
  }
  return true;
}

[[noreturn]] void run_child(int fd, const std::function<std::string()>& work,
                            const IsolationLimits& limits) {
  // The parent's crash handlers (a fuzzer's, a sanitizer's) must not run here: a crash of
  // the work is the child's death, reported to the parent by the signal.
  for (int s : {SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGABRT, SIGTRAP, SIGSYS})
    signal(s, SIG_DFL);
  sigset_t all;
  sigemptyset(&all);
  sigprocmask(SIG_SETMASK, &all, nullptr);
  if (__sanitizer_set_death_callback) __sanitizer_set_death_callback(die_of_sanitizer_report);
  if (const int null = open("/dev/null", O_WRONLY); null >= 0) {
    dup2(null, STDOUT_FILENO);
    dup2(null, STDERR_FILENO);
    close(null);
  }
  // The cap is what the caller measured (mesh_import.cpp: what the parent has mapped plus
  // half the machine's memory), so it holds under AddressSanitizer too, whose shadow and
  // allocator regions were mapped before the fork and count in what the parent has mapped.
  if (limits.address_space_bytes > 0) {
    const rlimit limit{limits.address_space_bytes, limits.address_space_bytes};
    setrlimit(RLIMIT_AS, &limit);
  }
  std::string frame;
  try {
    std::string result = work();
    frame.reserve(result.size() + 1);
    frame.push_back(kReturned);
    frame += result;
  } catch (const std::exception& e) {
    frame = std::string(1, kThrew) + e.what();
  } catch (...) {
    frame = std::string(1, kThrew) + "an exception of unknown type";
  }
  _exit(write_all(fd, frame.data(), frame.size()) ? 0 : 1);
}

}  // namespace

std::string describe_signal(int signal) {
  const char* name = sigabbrev_np(signal);
  const char* what = sigdescr_np(signal);
  std::string text = name ? std::string("SIG") + name : "signal " + std::to_string(signal);
  if (what) text += std::string(" (") + what + ")";
  return text;
}

IsolatedOutcome run_isolated(const std::function<std::string()>& work, const IsolationLimits& limits) {
  IsolatedOutcome outcome;
  int fds[2];
  if (pipe2(fds, O_CLOEXEC) != 0) {
    outcome.message = std::string("pipe: ") + std::strerror(errno);
    return outcome;
  }
  const pid_t pid = fork();
  if (pid < 0) {
    outcome.message = std::string("fork: ") + std::strerror(errno);
    close(fds[0]);
    close(fds[1]);
    return outcome;
  }
  if (pid == 0) {
    close(fds[0]);
    run_child(fds[1], work, limits);
  }
  close(fds[1]);

  // Read until the child closes its end (it exits), or until the deadline.
  using Clock = std::chrono::steady_clock;
  const auto deadline = Clock::now() + std::chrono::duration_cast<Clock::duration>(
                                           std::chrono::duration<double>(limits.seconds));
  std::string frame;
  bool timed_out = false;
  char buffer[1 << 16];
  for (;;) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Clock::now());
    if (left.count() <= 0) {
      timed_out = true;
      break;
    }
    pollfd p{fds[0], POLLIN, 0};
    const int ready = poll(&p, 1, int(std::min<long long>(left.count(), 1000)));
    if (ready < 0 && errno == EINTR) continue;
    if (ready < 0) break;
    if (ready == 0) continue;
    const ssize_t n = read(fds[0], buffer, sizeof buffer);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;  // end of file: the child is done (or died)
    frame.append(buffer, size_t(n));
  }
  close(fds[0]);
  if (timed_out) kill(pid, SIGKILL);
  int status = 0;
  while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  if (timed_out) {
    outcome.kind = IsolatedOutcome::Kind::TimedOut;
    return outcome;
  }
  if (WIFSIGNALED(status)) {
    outcome.kind = IsolatedOutcome::Kind::Crashed;
    outcome.signal = WTERMSIG(status);
    return outcome;
  }
  const int exit_status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  if (exit_status != 0 || frame.empty() || (frame[0] != kReturned && frame[0] != kThrew)) {
    outcome.kind = IsolatedOutcome::Kind::Crashed;
    outcome.exit_status = exit_status;
    return outcome;
  }
  outcome.kind = frame[0] == kReturned ? IsolatedOutcome::Kind::Returned : IsolatedOutcome::Kind::Threw;
  (outcome.kind == IsolatedOutcome::Kind::Returned ? outcome.bytes : outcome.message) = frame.substr(1);
  return outcome;
}

}  // namespace ldm
