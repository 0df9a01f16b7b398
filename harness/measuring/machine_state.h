#pragma once
// The state of the machine that moves a time without changing the work: its load, the CPU's
// frequency governor and clock, and on NVIDIA the GPU's SM clock, power and throttle
// reasons. Sampled at the start and end of every repetition and recorded beside its times
// (load_average_start, cpu_mhz_end, gpu_sm_clock_mhz_start, ...), so that a time can be
// read against the state it was measured in; a clock that changed, or throttling, during a
// repetition is warned about in status_detail (as nvbench's throttle detection does).
// Nothing here is ever required: what cannot be read is left out of the record.
#include <optional>
#include <string>

#include "harness/measure/clock_warmup.h"
#include "harness/records/record.h"

namespace ldm {

struct GpuClockState {
  double sm_clock_mhz = 0;
  double power_w = 0;
  std::string throttle_reasons;  // nvidia-smi's active bit mask, "0x0000000000000000" = none
  double max_sm_clock_mhz = 0;   // clocks.max.sm; 0 where not read
};

struct MachineState {
  std::optional<double> load_average;  // 1 minute (getloadavg)
  std::string cpu_governor;            // cpufreq scaling_governor of CPU 0, where readable
  std::optional<double> cpu_mhz;       // mean "cpu MHz" of /proc/cpuinfo, where given
  std::optional<GpuClockState> gpu;
};

// What the GPU's state is read for: nvidia-smi's device index (the CUDA ordinal of the
// context's device where known) and whether to ask at all (an NVIDIA renderer).
struct GpuStateQuery {
  bool nvidia = false;
  int index = 0;
};

// This machine's 1-minute load average, where readable.
std::optional<double> current_load_average();

// The CPUs other processes keep busy now: the busy share of every CPU's time over `seconds`
// (/proc/stat), times the CPUs, while this process sleeps. Unlike the load average, which
// lags a minute behind, it does not count a run that has just ended: after ldmbench's own
// sweep the 1-minute average stays near 1-2 on an idle machine, and the calibration took
// that for a change of load and probed again (docs/timing.md, "Run-to-run spread").
std::optional<double> busy_cpus_now(double seconds = 0.25);

// The aggregate "cpu" line of /proc/stat as busy and total ticks; nullopt when absent.
struct CpuTicks {
  unsigned long long busy = 0, total = 0;
};
std::optional<CpuTicks> parse_cpu_ticks(const std::string& proc_stat);
// Busy CPUs between two readings of `cpus` CPUs; nullopt when no tick passed.
std::optional<double> busy_cpus_between(const CpuTicks& before, const CpuTicks& after, int cpus);

MachineState sample_machine_state(const GpuStateQuery& gpu);

// The GPU's SM clock and its maximum now (nvidia-smi), for the clock warm-up; nullopt where
// it cannot be read.
std::optional<GpuClockReading> read_gpu_clock(const GpuStateQuery& gpu);

// nvidia-smi --query-gpu=clocks.sm,power.draw,clocks_throttle_reasons.active[,clocks.max.sm]
// --format=csv,noheader,nounits output, one line; nullopt when it does not parse.
std::optional<GpuClockState> parse_nvidia_smi_clocks(const std::string& line);

// Sets the *_start and *_end columns of what both samples hold.
void set_machine_state_columns(Record& record, const MachineState& start, const MachineState& end);

// The status_detail warning when the CPU clock moved by more than 10 %, the GPU's SM clock
// by more than 5 % or sat below 90 % of its maximum at either end, or the GPU reported a
// throttle reason at either end; "" otherwise.
std::string clock_change_warning(const MachineState& start, const MachineState& end);

}  // namespace ldm
