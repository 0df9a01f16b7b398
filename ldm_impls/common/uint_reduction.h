#pragma once
// A GPU reduction of a uint buffer to its sum, maximum and number of non-empty items, read
// back as three words (shaders/ldm/common/reduce_uint.comp). What a structure reads from its
// own storage to know what a build needed (the fixed arrays' deepest pixel, the HA-buffer's
// stored entries) and what the timed census reduces its counts with: the sizes come from the
// GPU, and only three words cross to the host.
#include <cstdint>

#include "harness/gl/gl_objects.h"

namespace ldm {

struct UintReductionResult {
  uint64_t sum = 0;  // 32-bit on the GPU: exact below 2^32 (every total here fits a block)
  uint32_t max = 0;
  uint64_t nonempty = 0;
};

class UintReduction {
 public:
  UintReduction();
  // Reduces the first `items` items of `buffer`, each `words_per_item` words (its first word
  // the value), skipping items whose words all equal `empty`. Waits for the result.
  UintReductionResult run(const GlBuffer& buffer, uint64_t items, uint32_t words_per_item = 1,
                          uint32_t empty = 0) const;

 private:
  GlProgram program_;
  mutable GlBuffer result_;
};

}  // namespace ldm
