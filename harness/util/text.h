#pragma once
// Small text helpers shared across the harness.
#include <cstdio>
#include <string>
#include <vector>

namespace ldm {

// "a, b, c": the items in order with `separator` between them (an empty first item adds no
// separator before the second, as every caller's lists of names never hold one).
inline std::string joined(const std::vector<std::string>& items, const std::string& separator = ", ") {
  std::string out;
  for (const auto& item : items) out += (out.empty() ? "" : separator) + item;
  return out;
}

// `x` printed as %.Ng with N = `digits` significant digits (6: printf's %g), so that 1e-50 and
// 4e+38 read as given rather than as 0.000000 or 38 digits.
inline std::string format_significant(double x, int digits = 6) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.*g", digits, x);
  return buffer;
}

}  // namespace ldm
