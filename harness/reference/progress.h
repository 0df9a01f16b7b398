#pragma once
// A one-line progress display (percentage and ETA) for long CPU renders. It stays silent for
// the first `delay_seconds` so that short renders (tests, cache hits) print nothing, redraws
// at most every `interval_seconds`, and overwrites its line with '\r'.
#include <chrono>
#include <iosfwd>
#include <string>

namespace ldm {

class ProgressDisplay {
 public:
  // `out == nullptr` disables the display.
  ProgressDisplay(std::string label, std::ostream* out, double delay_seconds = 2.0,
                  double interval_seconds = 0.25);
  // Writes to stderr only when `enabled` and stderr is a terminal (never into logs or pipes).
  static ProgressDisplay on_stderr(std::string label, bool enabled);

  // `fraction` of the work done, in [0, 1].
  void update(double fraction);
  // Ends the line (with the total time) if anything was shown.
  void finish();

 private:
  using Clock = std::chrono::steady_clock;
  double seconds_since(Clock::time_point t) const;

  std::string label_;
  std::ostream* out_;
  double delay_seconds_, interval_seconds_;
  Clock::time_point start_ = Clock::now();
  Clock::time_point last_draw_{};
  bool shown_ = false;
};

}  // namespace ldm
