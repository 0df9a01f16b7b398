#pragma once
// Small text helpers shared across the harness.
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

}  // namespace ldm
