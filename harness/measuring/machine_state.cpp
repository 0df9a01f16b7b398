#include "harness/measuring/machine_state.h"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <thread>

#include "harness/records/harness_columns.h"
#include "harness/util/process.h"

namespace ldm {
namespace {

std::string first_line_of(const char* path) {
  std::ifstream in(path);
  std::string line;
  if (in) std::getline(in, line);
  return line;
}

std::optional<double> mean_cpu_mhz() {
  std::ifstream in("/proc/cpuinfo");
  std::string line;
  double sum = 0;
  int count = 0;
  while (std::getline(in, line)) {
    if (line.rfind("cpu MHz", 0) != 0) continue;
    const size_t colon = line.find(':');
    if (colon == std::string::npos) continue;
    char* end = nullptr;
    const double mhz = std::strtod(line.c_str() + colon + 1, &end);
    if (end != line.c_str() + colon + 1 && mhz > 0) {
      sum += mhz;
      ++count;
    }
  }
  if (!count) return std::nullopt;
  return sum / count;
}

bool nvidia_smi_on_path() {
  const char* path = std::getenv("PATH");
  if (!path) return false;
  std::stringstream folders(path);
  for (std::string folder; std::getline(folders, folder, ':');)
    if (!folder.empty() && std::ifstream(folder + "/nvidia-smi").good()) return true;
  return false;
}

std::string trimmed(const std::string& s) {
  const size_t b = s.find_first_not_of(" \t\r\n");
  if (b == std::string::npos) return "";
  return s.substr(b, s.find_last_not_of(" \t\r\n") - b + 1);
}

bool throttled(const GpuClockState& gpu) {
  // nvidia-smi prints the mask in hex; 0x1 alone is "GPU idle", which is not throttling.
  const unsigned long long mask = std::strtoull(gpu.throttle_reasons.c_str(), nullptr, 16);
  return (mask & ~1ull) != 0;
}

}  // namespace

std::optional<double> current_load_average() {
  double load[1];
  if (::getloadavg(load, 1) != 1) return std::nullopt;
  return load[0];
}

std::optional<CpuTicks> parse_cpu_ticks(const std::string& proc_stat) {
  std::istringstream in(proc_stat);
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind("cpu ", 0) != 0) continue;
    std::istringstream fields(line.substr(4));
    // user nice system idle iowait irq softirq steal (guest time is inside user and nice)
    unsigned long long value[8] = {};
    int read = 0;
    while (read < 8 && fields >> value[read]) ++read;
    if (read < 4) return std::nullopt;
    CpuTicks ticks;
    for (int i = 0; i < read; ++i) ticks.total += value[i];
    ticks.busy = ticks.total - value[3] - (read > 4 ? value[4] : 0);
    return ticks;
  }
  return std::nullopt;
}

std::optional<double> busy_cpus_between(const CpuTicks& before, const CpuTicks& after, int cpus) {
  if (after.total <= before.total || after.busy < before.busy || cpus < 1) return std::nullopt;
  return double(after.busy - before.busy) / double(after.total - before.total) * cpus;
}

std::optional<double> busy_cpus_now(double seconds) {
  const auto read = []() -> std::optional<CpuTicks> {
    std::ifstream file("/proc/stat");
    if (!file) return std::nullopt;
    std::stringstream text;
    text << file.rdbuf();
    return parse_cpu_ticks(text.str());
  };
  const auto before = read();
  if (!before) return std::nullopt;
  std::this_thread::sleep_for(std::chrono::duration<double>(seconds));
  const auto after = read();
  const long cpus = ::sysconf(_SC_NPROCESSORS_ONLN);
  if (!after || cpus < 1) return std::nullopt;
  return busy_cpus_between(*before, *after, int(cpus));
}

std::optional<GpuClockState> parse_nvidia_smi_clocks(const std::string& line) {
  std::stringstream in(line);
  std::string clock, power, reasons, max_clock;
  if (!std::getline(in, clock, ',') || !std::getline(in, power, ',') || !std::getline(in, reasons, ','))
    return std::nullopt;
  std::getline(in, max_clock);  // clocks.max.sm: absent from older queries
  char* end = nullptr;
  GpuClockState out;
  clock = trimmed(clock);
  out.sm_clock_mhz = std::strtod(clock.c_str(), &end);
  if (clock.empty() || *end) return std::nullopt;
  power = trimmed(power);
  out.power_w = std::strtod(power.c_str(), &end);
  if (power.empty() || *end) out.power_w = std::nan("");  // "[N/A]" on some boards
  out.throttle_reasons = trimmed(reasons);
  max_clock = trimmed(max_clock);
  out.max_sm_clock_mhz = std::strtod(max_clock.c_str(), &end);
  if (max_clock.empty() || *end || !(out.max_sm_clock_mhz > 0)) out.max_sm_clock_mhz = 0;
  return out;
}

static std::optional<GpuClockState> query_gpu_clocks(const GpuStateQuery& gpu) {
  if (!gpu.nvidia || !nvidia_smi_on_path()) return std::nullopt;
  const ProcessResult r =
      run_process({"nvidia-smi", "--query-gpu=clocks.sm,power.draw,clocks_throttle_reasons.active,clocks.max.sm",
                   "--format=csv,noheader,nounits", "-i", std::to_string(gpu.index)},
                  true);
  if (!r.started || r.status != 0) return std::nullopt;
  return parse_nvidia_smi_clocks(r.output.substr(0, r.output.find('\n')));
}

std::optional<GpuClockReading> read_gpu_clock(const GpuStateQuery& gpu) {
  const std::optional<GpuClockState> state = query_gpu_clocks(gpu);
  if (!state) return std::nullopt;
  return GpuClockReading{state->sm_clock_mhz, state->max_sm_clock_mhz};
}

MachineState sample_machine_state(const GpuStateQuery& gpu) {
  MachineState s;
  s.load_average = current_load_average();
  s.cpu_governor = first_line_of("/sys/devices/system/cpu/cpu0/cpufreq/scaling_governor");
  s.cpu_mhz = mean_cpu_mhz();
  s.gpu = query_gpu_clocks(gpu);
  return s;
}

void set_machine_state_columns(Record& r, const MachineState& start, const MachineState& end) {
  if (start.load_average && end.load_average) {
    r.set("load_average_start", *start.load_average);
    r.set("load_average_end", *end.load_average);
  }
  if (!start.cpu_governor.empty()) r.set(columns::kCpuGovernor, start.cpu_governor);
  if (start.cpu_mhz && end.cpu_mhz) {
    r.set("cpu_mhz_start", *start.cpu_mhz);
    r.set("cpu_mhz_end", *end.cpu_mhz);
  }
  if (start.gpu && end.gpu) {
    r.set("gpu_sm_clock_mhz_start", start.gpu->sm_clock_mhz);
    r.set("gpu_sm_clock_mhz_end", end.gpu->sm_clock_mhz);
    if (std::isfinite(start.gpu->power_w) && std::isfinite(end.gpu->power_w)) {
      r.set("gpu_power_w_start", start.gpu->power_w);
      r.set("gpu_power_w_end", end.gpu->power_w);
    }
    r.set("gpu_throttle_reasons_start", start.gpu->throttle_reasons);
    r.set("gpu_throttle_reasons_end", end.gpu->throttle_reasons);
    if (start.gpu->max_sm_clock_mhz > 0) r.set(columns::kGpuSmClockMaxMhz, start.gpu->max_sm_clock_mhz);
  }
}

std::string clock_change_warning(const MachineState& start, const MachineState& end) {
  char text[200];
  if (start.gpu && end.gpu) {
    if (throttled(*start.gpu) || throttled(*end.gpu)) {
      std::snprintf(text, sizeof text, "GPU throttled during the repetition (reasons %s at the start, %s at the end)",
                    start.gpu->throttle_reasons.c_str(), end.gpu->throttle_reasons.c_str());
      return text;
    }
    const double a = start.gpu->sm_clock_mhz, b = end.gpu->sm_clock_mhz;
    if (a > 0 && std::fabs(b - a) > 0.05 * a) {
      std::snprintf(text, sizeof text, "GPU SM clock changed during the repetition (%.0f to %.0f MHz)", a, b);
      return text;
    }
    // Steady but low: a GPU that never left its idle clock (345 MHz against 1980 on an H200)
    // measures up to 5 times slower without any change to warn about.
    const double max = start.gpu->max_sm_clock_mhz;
    if (max > 0 && std::min(a, b) < kWorkingClockFraction * max) {
      std::snprintf(text, sizeof text,
                    "GPU SM clock below %.0f %% of its %.0f MHz maximum during the repetition (%.0f MHz at the start, "
                    "%.0f at the end)",
                    100 * kWorkingClockFraction, max, a, b);
      return text;
    }
  }
  if (start.cpu_mhz && end.cpu_mhz && *start.cpu_mhz > 0 &&
      std::fabs(*end.cpu_mhz - *start.cpu_mhz) > 0.10 * *start.cpu_mhz) {
    std::snprintf(text, sizeof text, "CPU clock changed during the repetition (%.0f to %.0f MHz)", *start.cpu_mhz,
                  *end.cpu_mhz);
    return text;
  }
  return "";
}

}  // namespace ldm
