#pragma once
// Graceful stop on SIGINT / SIGTERM for long sweeps: the first signal only raises a flag;
// long loops (the reference renderer's tiles, the sweep between configurations) poll it and
// abandon their work cleanly by throwing Interrupted. A second signal kills the process at
// once (the default action is restored after the first).
#include <stdexcept>

namespace ldm {

class Interrupted : public std::runtime_error {
 public:
  explicit Interrupted(int signal);
  int signal() const { return signal_; }

 private:
  int signal_;
};

// Installs the handlers for SIGINT and SIGTERM (idempotent).
void install_stop_handlers();
// The signal received since install_stop_handlers(), or 0.
int stop_signal();
// Throws Interrupted when a stop was requested.
void throw_if_stop_requested();

}  // namespace ldm
