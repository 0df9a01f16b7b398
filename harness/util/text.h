#pragma once
// Small text helpers shared across the harness.
#include <algorithm>
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

// The non-empty pieces of `text` between the occurrences of `separator`, in order ("a,,b" split
// on "," is a and b; "" is none).
inline std::vector<std::string> split_nonempty(const std::string& text, const std::string& separator) {
  std::vector<std::string> pieces;
  size_t start = 0;
  while (start <= text.size()) {
    const size_t end = std::min(text.find(separator, start), text.size());
    if (end > start) pieces.push_back(text.substr(start, end - start));
    start = end + separator.size();
  }
  return pieces;
}

// `x` printed as %.Ng with N = `digits` significant digits (6: printf's %g), so that 1e-50 and
// 4e+38 read as given rather than as 0.000000 or 38 digits.
inline std::string format_significant(double x, int digits = 6) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.*g", digits, x);
  return buffer;
}

}  // namespace ldm
