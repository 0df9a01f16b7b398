#include "harness/run/sweep_progress.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>

namespace ldm {

std::string format_duration(double seconds) {
  const long s = std::lround(std::max(0.0, seconds));
  char buffer[32];
  if (s < 60)
    std::snprintf(buffer, sizeof buffer, "%lds", s);
  else if (s < 3600)
    std::snprintf(buffer, sizeof buffer, "%ldm%02lds", s / 60, s % 60);
  else
    std::snprintf(buffer, sizeof buffer, "%ldh%02ldm", s / 3600, (s % 3600) / 60);
  return buffer;
}

SweepProgress::SweepProgress(size_t total, std::ostream* out) : total_(total), out_(out) {}

std::ostream* SweepProgress::stderr_if_terminal() { return ::isatty(STDERR_FILENO) ? &std::cerr : nullptr; }

std::string SweepProgress::format(size_t done, size_t total, double elapsed) {
  constexpr int kWidth = 24;
  const double fraction = total ? double(done) / double(total) : 1.0;
  const int filled = int(fraction * kWidth);
  std::string bar = "sweep [" + std::string(size_t(filled), '#') + std::string(size_t(kWidth - filled), '-') + "] ";
  char counts[64];
  std::snprintf(counts, sizeof counts, "%zu/%zu %d%% ", done, total, int(fraction * 100.0));
  std::string text = bar + counts + format_duration(elapsed);
  if (done > 0 && done < total)
    text += ", ETA " + format_duration(elapsed / double(done) * double(total - done));
  return text;
}

void SweepProgress::skip(size_t count) { total_ -= std::min(count, total_ - std::min(total_, done_)); }

void SweepProgress::finished_one() { ++done_; }

void SweepProgress::show(const std::string& current) {
  if (!out_) return;
  const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  *out_ << "\r\033[K" << format(done_, total_, elapsed) << "  " << current << std::flush;
  shown_ = true;
}

void SweepProgress::erase() {
  if (!out_ || !shown_) return;
  *out_ << "\r\033[K" << std::flush;
  shown_ = false;
}

}  // namespace ldm
