#pragma once
// The two-sided Mann-Whitney U test, the test Google Benchmark's compare.py applies to the
// repetitions of two runs. Normal approximation with tie and continuity correction (SciPy's
// mannwhitneyu(..., method="asymptotic")): no assumption that frame times are normal.
#include <cstddef>
#include <vector>

namespace ldm {

struct UTestResult {
  double u = 0;        // U statistic of the first sample
  double p_value = 1;  // two-sided; 1 when every value ties
};

// Both samples must be non-empty (throws std::invalid_argument otherwise).
UTestResult mann_whitney_u(const std::vector<double>& a, const std::vector<double>& b);

// compare.py's sample-size rule: below this many samples per side the test is weak and a
// warning says so (its UTEST_OPTIMAL_REPETITIONS).
constexpr size_t kUTestOptimalSamples = 9;
// ... and below this it is not run at all (UTEST_MIN_REPETITIONS).
constexpr size_t kUTestMinSamples = 2;

}  // namespace ldm
