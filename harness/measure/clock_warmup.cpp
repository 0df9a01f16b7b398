#include "harness/measure/clock_warmup.h"

#include <cmath>
#include <cstdio>
#include <string>

namespace ldm {

bool at_working_clock(const GpuClockReading& now, const std::optional<GpuClockReading>& previous) {
  if (!(now.max_mhz > 0)) return true;  // no maximum to judge against: nothing to wait for
  if (now.mhz >= kWorkingClockFraction * now.max_mhz) return true;
  const bool steady = previous && previous->mhz > 0 &&
                      std::fabs(now.mhz - previous->mhz) <= kSteadyClockTolerance * previous->mhz;
  return steady && now.mhz >= kSteadyClockFraction * now.max_mhz;
}

ClockWarmupResult warm_until_working_clock(const ClockWarmup& warmup, const std::function<void()>& frame,
                                           const std::function<double()>& now_seconds) {
  ClockWarmupResult result;
  if (!warmup.read || !(warmup.limit_seconds > 0)) return result;
  std::optional<GpuClockReading> reading = warmup.read();
  if (!reading) return result;
  result.checked = true;
  std::optional<GpuClockReading> previous;
  const double started = now_seconds();
  while (!at_working_clock(*reading, previous) && now_seconds() - started < warmup.limit_seconds) {
    const double slice_started = now_seconds();
    do {
      frame();
      ++result.frames;
    } while (now_seconds() - slice_started < warmup.slice_seconds);
    previous = reading;
    const std::optional<GpuClockReading> next = warmup.read();
    if (!next) break;  // the reader stopped answering: keep the last reading
    reading = next;
  }
  result.seconds = now_seconds() - started;
  result.last = *reading;
  result.reached = at_working_clock(*reading, previous);
  return result;
}

std::string clock_warmup_warning(const ClockWarmupResult& result) {
  if (!result.checked || result.reached) return "";
  char text[240];
  std::snprintf(text, sizeof text,
                "GPU SM clock %.0f MHz of its %.0f MHz maximum after %.1f s of added warm-up (%d frames): measured "
                "below its working clock, times are slower than the device's",
                result.last.mhz, result.last.max_mhz, result.seconds, result.frames);
  return text;
}

}  // namespace ldm
