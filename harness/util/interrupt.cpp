#include "harness/util/interrupt.h"

#include <csignal>
#include <string>

namespace ldm {
namespace {

volatile std::sig_atomic_t received_signal = 0;

extern "C" void on_stop_signal(int signal) { received_signal = signal; }

}  // namespace

Interrupted::Interrupted(int signal)
    : std::runtime_error("interrupted by signal " + std::to_string(signal)), signal_(signal) {}

void install_stop_handlers() {
  struct sigaction action {};
  action.sa_handler = on_stop_signal;
  sigemptyset(&action.sa_mask);
  // SA_RESETHAND: the default action is back after the first signal, so a second one ends
  // the process. SA_RESTART: the journal's write and fsync are not cut short by the signal.
  action.sa_flags = SA_RESETHAND | SA_RESTART;
  sigaction(SIGINT, &action, nullptr);
  sigaction(SIGTERM, &action, nullptr);
}

int stop_signal() { return int(received_signal); }

void throw_if_stop_requested() {
  if (const int signal = stop_signal()) throw Interrupted(signal);
}

}  // namespace ldm
