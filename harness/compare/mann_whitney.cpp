#include "harness/compare/mann_whitney.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

namespace ldm {

UTestResult mann_whitney_u(const std::vector<double>& a, const std::vector<double>& b) {
  if (a.empty() || b.empty()) throw std::invalid_argument("mann_whitney_u: empty sample");
  const double n1 = double(a.size()), n2 = double(b.size()), n = n1 + n2;
  std::vector<std::pair<double, int>> pooled;  // value, which sample
  for (double v : a) pooled.emplace_back(v, 0);
  for (double v : b) pooled.emplace_back(v, 1);
  std::sort(pooled.begin(), pooled.end());
  // Midranks, and the tie term sum(t^3 - t) of the variance correction.
  double rank_sum_a = 0, tie_term = 0;
  for (size_t i = 0; i < pooled.size();) {
    size_t j = i;
    while (j < pooled.size() && pooled[j].first == pooled[i].first) ++j;
    const double t = double(j - i), midrank = (double(i + 1) + double(j)) / 2;
    for (size_t k = i; k < j; ++k)
      if (pooled[k].second == 0) rank_sum_a += midrank;
    tie_term += t * t * t - t;
    i = j;
  }
  UTestResult result;
  result.u = rank_sum_a - n1 * (n1 + 1) / 2;
  const double u_max = std::max(result.u, n1 * n2 - result.u);
  const double mean = n1 * n2 / 2;
  const double variance = n1 * n2 / 12 * ((n + 1) - tie_term / (n * (n - 1)));
  if (variance <= 0) return result;  // every value ties: no evidence of a difference
  const double z = (u_max - mean - 0.5) / std::sqrt(variance);
  result.p_value = std::min(1.0, std::erfc(z / std::sqrt(2.0)));
  return result;
}

}  // namespace ldm
