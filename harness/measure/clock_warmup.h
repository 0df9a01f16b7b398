#pragma once
// Warm-up until the GPU runs at its working clock. A GPU left idle (while the CPU computes a
// reference, writes images or compiles shaders) drops its SM clock, and ramps it again only
// after some hundred milliseconds of load: on an NVIDIA H200 the first repetition of 42 of
// 84 configurations of the GPU suite ran 1.2 to 5.5 times slower than the next two, at
// 345 to 900 MHz instead of 1980 (docs/measured/gpu-suite.md). A fixed count of warm-up
// frames cannot cover that: 2 frames of 4 ms are 8 ms. So after the fixed warm-up frames,
// where the clock can be read, more warm-up frames run until the clock reaches its working
// level or a time limit passes; the record says how many ran and what the clock was.
#include <functional>
#include <optional>
#include <string>

namespace ldm {

// One reading of the GPU's SM clock and the most it can reach (nvidia-smi clocks.sm,
// clocks.max.sm), MHz.
struct GpuClockReading {
  double mhz = 0;
  double max_mhz = 0;
};

// Working clock: at least 90 % of the maximum, or steady (two readings a slice apart within
// 3 %) at at least 75 % of it, where a power or thermal limit holds the clock below its
// maximum under sustained load.
inline constexpr double kWorkingClockFraction = 0.90;
inline constexpr double kSteadyClockFraction = 0.75;
inline constexpr double kSteadyClockTolerance = 0.03;
bool at_working_clock(const GpuClockReading& now, const std::optional<GpuClockReading>& previous);

struct ClockWarmup {
  // Reads the clock; nullopt where it cannot be read (not NVIDIA, no nvidia-smi): then no
  // frame is added. Unset: off.
  std::function<std::optional<GpuClockReading>()> read;
  double limit_seconds = 3.0;  // added warm-up's wall time, at most (0: off)
  double slice_seconds = 0.1;  // frames run between two readings (keeps the GPU loaded)
};

struct ClockWarmupResult {
  bool checked = false;  // a reading was made
  bool reached = false;  // the last reading was at the working clock
  int frames = 0;        // warm-up frames added
  double seconds = 0;    // their wall time
  GpuClockReading last;  // the last reading
};

// Reads the clock; while it is below the working clock and the limit has not passed, runs
// `frame` for a slice (at least one frame) and reads again. `now_seconds` is a monotonic
// clock (injected so that the tests need no GPU).
ClockWarmupResult warm_until_working_clock(const ClockWarmup& warmup, const std::function<void()>& frame,
                                           const std::function<double()>& now_seconds);

// The status_detail warning for a warm-up that ended below the working clock, "" otherwise.
std::string clock_warmup_warning(const ClockWarmupResult& result);

}  // namespace ldm
