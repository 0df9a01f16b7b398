#include "harness/util/hash.h"

#include <cstdio>

namespace ldm {
std::string hex64(uint64_t value) {
  char buffer[17];
  std::snprintf(buffer, sizeof buffer, "%016llx", static_cast<unsigned long long>(value));
  return buffer;
}
}  // namespace ldm
