#pragma once
// How far the median time of one run lands from the median of the same configuration run
// again in another process a few minutes later, on this device, driver and machine: the
// run-to-run spread. A run's own frames cannot show it (they share its process, its
// caches, its minute of the machine's load), so a single run's interval of the median is
// far too narrow to say "run it again and you get this" (docs/timing.md, "Run-to-run
// spread"). The spread is measured by a probe (harness/measuring/calibration.h: A/A runs in
// separate processes), cached, and widens every record's interval
// (harness/measuring/timing_columns.h).
//
// The spread is the root mean square of log(median_a / median_b) over pairs of processes
// measuring the same configuration and sub-pass: the standard deviation of the difference
// between two runs' log medians (drift included), so z * spread is the half-width (in log
// space) that holds another run's median with probability about that of z.
#include <cstddef>
#include <cstdint>
#include <limits>
#include <map>
#include <string>
#include <vector>

namespace ldm {


// One probe process's medians: configuration id + "/" + sub-pass -> median ms.
using ProbeMedians = std::map<std::string, double>;

// One probe as measured, kept in the cache so that later probes of the day pool with it.
struct ProbeEntry {
  double spread = std::numeric_limits<double>::quiet_NaN();  // this probe's own RMS log ratio
  size_t pairs = 0;
  size_t processes = 0;
  int64_t measured_at = 0;
  double load_average = std::numeric_limits<double>::quiet_NaN();
  std::string commit;                 // the build that probed
  std::vector<ProbeMedians> medians;  // each process's (none in an entry written before)
  // CPUs other processes kept busy just before the probe (busy_cpus_now(); NaN in an entry
  // written before it was read): the load the spread belongs to.
  double busy_cpus = std::numeric_limits<double>::quiet_NaN();
};

struct RunToRunSpread {
  double spread = std::numeric_limits<double>::quiet_NaN();  // RMS log ratio, see above
  size_t pairs = 0;              // log ratios it is the RMS of (every pooled probe's)
  size_t processes = 0;          // probe processes (every pooled probe's)
  int64_t measured_at = 0;       // Unix time of the probe's end
  double load_average = std::numeric_limits<double>::quiet_NaN();  // 1-minute, at the probe
  double busy_cpus = std::numeric_limits<double>::quiet_NaN();     // other processes', before it
  double probe_seconds = 0;      // the probe's wall time
  // What it holds for (the cache key, calibration_key(), but for the commit that probed).
  std::string device, driver, host, commit;
  std::string source;            // where this value came from: "probe", "cache FILE", "file FILE"
  std::vector<ProbeMedians> medians;  // a fresh probe's processes' medians (pooling reads them)
  // The day's probes (the newest last), the pooled ones and the others; `pooled_probes` of
  // them (at this one's load) make `spread`, `pairs` and `processes`.
  std::vector<ProbeEntry> probes;
  size_t pooled_probes = 1;
};


// The spread from several processes' medians of the same configurations: every pair of
// processes, every key both hold with positive medians, one log ratio each. NaN (and 0
// pairs) with fewer than two processes or nothing in common.
RunToRunSpread spread_from_processes(const std::vector<ProbeMedians>& processes);

// Why a cached spread must be measured again, or "" when it holds: older than
// kCalibrationMaxAgeSeconds, or the machine's load now differs from the probe's by more than
// kCalibrationMaxLoadChange (the spread depends on the load). The load is the CPUs other
// processes keep busy (busy_cpus_now()) where both the entry and now have it, else the
// 1-minute load average: the average lags a minute behind, so right after a run of
// ldmbench's own it reads 1-2 on an idle machine (2026-12-05: the advise comparison's
// Cornell box probed again for that, 6 s of its 17.6 s, and each needless probe drew a new
// spread between 0.04 and 0.30).
inline constexpr int64_t kCalibrationMaxAgeSeconds = 24 * 3600;
inline constexpr double kCalibrationMaxLoadChange = 0.5;
std::string calibration_staleness(const RunToRunSpread& cached, int64_t now, double load_average_now,
                                  double busy_cpus_now = std::numeric_limits<double>::quiet_NaN());

// Whether two probes (or a probe and now) saw about the same load: busy CPUs within
// kCalibrationMaxLoadChange where both have them, else load averages within it; false when
// neither is known for both.
bool same_load(double load_average_a, double busy_cpus_a, double load_average_b, double busy_cpus_b);

// One probe of a few processes is a rough estimate, and of the wrong time scale: its
// processes run back to back within seconds, while the spread that matters is between runs
// minutes or hours apart. Probes seconds apart at the same load drew 0.069-0.082 and
// 0.17-0.23, and an advise measured in a minute 30 % slower than the exhaustive runs'
// (2026-12-04, docs/timing.md). So a fresh probe is pooled with the earlier probes of the last
// kCalibrationMaxAgeSeconds, by the same build, measured at a load within
// kCalibrationMaxLoadChange of its own: the spread is spread_from_processes() over all their
// processes together, so that every pair of processes of two probes minutes or hours apart
// gives its log ratios too. (An entry written before probes kept their medians pools by its
// RMS: spread = sqrt((S + s_i^2 pairs_i) / (P + pairs_i)).) `earlier` is the cached entry's
// probe list; the result lists the day's probes (at any load, at most
// kCalibrationKeptProbes, the newest kept) with the fresh one last.
inline constexpr size_t kCalibrationKeptProbes = 16;
RunToRunSpread pool_with_earlier_probes(const RunToRunSpread& fresh, const std::vector<ProbeEntry>& earlier,
                                        int64_t now);

// Where a record's K repetitions ran: each in a process of its own (--isolation process), or
// all in this one (--isolation context), where they share the process's offset from other
// runs: repetitions in one process do not average that offset away.
enum class RepetitionProcesses { Separate, Shared };

// The half-width, relative to the median, of an interval that should hold another run's
// median, in log space (the interval is [median * exp(-h), median * exp(h)]), from the
// within-run half-width `within` (the frames' order-statistic interval, or the repetitions'
// t interval) and the run-to-run spread s (the RMS log ratio between single-repetition runs
// in separate processes: both runs' process offsets and their repetitions' noise):
//  - one repetition: sqrt(within^2 + (z s)^2); its own process offset is in s, not in its
//    frames' interval;
//  - K repetitions in separate processes: sqrt(within^2 + (z s)^2 / (2K)); the t interval
//    holds this run's offsets, and the other run's median of K varies by s^2 / (2K) (s^2 is
//    the variance of a difference of two runs);
//  - K repetitions in one process: max(within, z s); the t interval sees only the noise
//    between repetitions, which s already holds, while the process offset they share is not
//    reduced by K (measured 2026-12-04, docs/timing.md: the K / 2K form held another run's
//    median in 64-78 % of 36 configurations when the second process ran 10-20 % faster).
double widened_log_half_width(double within_log_half_width, double spread, size_t repetitions, double z,
                              RepetitionProcesses processes);

// The least frame precision worth reaching where another run's median lands the spread away
// anyway: a repetition's median interval a third of the spread between two processes' medians
// (z s / (3 sqrt 2), relative; s / sqrt 2 is one process's offset). More frames than that
// narrow the widened interval of one repetition by at most 3 % (sqrt(1 + 1/18)) and the
// interval of K repetitions in separate processes by at most 5 % (their medians' variance
// s^2/2 + s^2/18): on a noisy machine (s 0.2, z s 0.39: a floor of 0.09) they only cost
// time; on a quiet one (s 0.05: 0.023) the usual 3 % target stands. 0 without a spread.
double frame_precision_floor(const RunToRunSpread* spread, double z);

// A file name for the cache entry of this device, driver and host (the build that probed
// is recorded in the entry, not keyed: the spread is the machine's).
std::string calibration_key(const std::string& device, const std::string& driver, const std::string& host);

// JSON text of a spread, and back (throws UserError naming `origin` on bad input).
std::string spread_to_json(const RunToRunSpread& spread);
RunToRunSpread spread_from_json(const std::string& text, const std::string& origin);

}  // namespace ldm
