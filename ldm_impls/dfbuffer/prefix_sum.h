#pragma once
// Parallel exclusive prefix sum of 32-bit counts on the GPU: the DF-buffer's "Prefix Sum"
// step (thesis §3.2.10, Figure 10), done with Thrust in [Comba et al. 2012] and here with
// compute shaders. Each workgroup scans one block of kScanBlock values in shared memory
// (a work-efficient up-sweep/down-sweep scan, Blelloch 1990) and emits the block's sum; the
// block sums are scanned the same way, recursively until one block remains, and each
// block then adds its scanned sum (uniform add). Shaders: shaders/ldm/dfbuffer/scan_*.comp.
#include <cstdint>
#include <vector>

#include "harness/gl/gl_objects.h"

namespace ldm {

class PrefixSum {
 public:
  static constexpr uint32_t kGroupSize = 256;    // invocations per workgroup
  static constexpr uint32_t kPerInvocation = 4;  // values each invocation scans serially
  static constexpr uint32_t kScanBlock = kGroupSize * kPerInvocation;

  // Prepares to scan `count` values (allocates the block sums of every level).
  explicit PrefixSum(uint64_t count);

  // output[i] = input[0] + ... + input[i - 1] for i in [0, count], so output[count] is the
  // total: output holds count + 1 values. Uses storage bindings 0-2; input and output must
  // be distinct buffers. Ends with a barrier, so later passes and downloads see the result.
  void run(const GlBuffer& input, const GlBuffer& output) const;

  uint64_t count() const { return count_; }
  size_t levels() const { return block_sums_.size(); }
  uint64_t scratch_bytes() const;  // the block sums of all levels

 private:
  void scan_level(const GlBuffer& input, uint64_t input_count, const GlBuffer& output,
                  uint64_t count, const GlBuffer& block_sums) const;
  void add_block_offsets(const GlBuffer& values, uint64_t count,
                         const GlBuffer& block_offsets) const;

  uint64_t count_ = 0;
  std::vector<GlBuffer> block_sums_;  // level l: one sum per block of level l
  GlProgram scan_program_, add_program_;
};

}  // namespace ldm
