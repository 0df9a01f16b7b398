#include "harness/reference/progress.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>

namespace ldm {
namespace {

std::string format_duration(double seconds) {
  char buffer[32];
  const long s = std::lround(std::max(0.0, seconds));
  if (s >= 3600)
    std::snprintf(buffer, sizeof buffer, "%ldh%02ldm", s / 3600, (s / 60) % 60);
  else if (s >= 60)
    std::snprintf(buffer, sizeof buffer, "%ldm%02lds", s / 60, s % 60);
  else
    std::snprintf(buffer, sizeof buffer, "%lds", s);
  return buffer;
}

}  // namespace

ProgressDisplay::ProgressDisplay(std::string label, std::ostream* out, double delay_seconds,
                                 double interval_seconds)
    : label_(std::move(label)),
      out_(out),
      delay_seconds_(delay_seconds),
      interval_seconds_(interval_seconds) {}

ProgressDisplay ProgressDisplay::on_stderr(std::string label, bool enabled) {
  const bool terminal = ::isatty(STDERR_FILENO) == 1;
  return ProgressDisplay(std::move(label), enabled && terminal ? &std::cerr : nullptr);
}

double ProgressDisplay::seconds_since(Clock::time_point t) const {
  return std::chrono::duration<double>(Clock::now() - t).count();
}

void ProgressDisplay::update(double fraction) {
  if (!out_) return;
  const double elapsed = seconds_since(start_);
  if (elapsed < delay_seconds_) return;
  if (shown_ && seconds_since(last_draw_) < interval_seconds_) return;
  fraction = std::clamp(fraction, 0.0, 1.0);
  char line[64];
  if (fraction > 0.0) {
    const std::string eta = format_duration(elapsed * (1.0 - fraction) / fraction);
    std::snprintf(line, sizeof line, "%5.1f%%  ETA %s   ", 100.0 * fraction, eta.c_str());
  } else {
    std::snprintf(line, sizeof line, "%5.1f%%  ETA ?   ", 0.0);
  }
  *out_ << '\r' << label_ << ": " << line << std::flush;
  shown_ = true;
  last_draw_ = Clock::now();
}

void ProgressDisplay::finish() {
  if (!out_ || !shown_) return;
  *out_ << '\r' << label_ << ": 100.0%  in " << format_duration(seconds_since(start_))
        << "          \n"
        << std::flush;
  shown_ = false;
}

}  // namespace ldm
