#pragma once
// The progress bar of a sweep on a terminal: "sweep [#####-----] 12/40 30% 1m02s, ETA 2m25s
// <configuration in flight>", drawn on stderr below the per-configuration lines (erased
// before each of them is printed) and only when stderr is a terminal, so that logs and pipes never see it. The ETA is the mean time
// of the configurations measured so far times those left.
#include <chrono>
#include <cstddef>
#include <iosfwd>
#include <string>

namespace ldm {

class SweepProgress {
 public:
  // `out == nullptr` disables the bar.
  SweepProgress(size_t total, std::ostream* out);
  static std::ostream* stderr_if_terminal();

  bool active() const { return out_ != nullptr; }
  void show(const std::string& current);  // draws the bar and the configuration in flight
  void finished_one();  // one more configuration (or repetition of one) done
  void skip(size_t count);  // `count` fewer to do (a failed configuration's other repetitions)
  void erase();         // clears the bar's line (before other output)

  // The bar's text for `done` of `total` after `elapsed` seconds (tests check it).
  static std::string format(size_t done, size_t total, double elapsed_seconds);

 private:
  size_t total_, done_ = 0;
  std::ostream* out_;
  bool shown_ = false;
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
};

// "42s", "3m05s", "2h01m".
std::string format_duration(double seconds);

}  // namespace ldm
