#include "ldm_impls/dfbuffer/prefix_sum.h"

#include "harness/gl/bindings.h"
#include "harness/util/error.h"
#include "ldm_impls/common/compute_grid.h"

namespace ldm {

namespace {

GlProgram scan_program(const std::string& file) {
  ShaderDefines defines;
  defines.set("SCAN_GROUP_SIZE", std::to_string(PrefixSum::kGroupSize) + "u");
  defines.set("SCAN_PER_INVOCATION", std::to_string(PrefixSum::kPerInvocation) + "u");
  return build_compute_program(file, defines);
}

}  // namespace

PrefixSum::PrefixSum(uint64_t count) : count_(count) {
  if (count + 1 >= (uint64_t(1) << 32))
    throw UserError("prefix sum: " + std::to_string(count) + " values exceed 32-bit indices");
  scan_program_ = scan_program("ldm/dfbuffer/scan_blocks.comp");
  add_program_ = scan_program("ldm/dfbuffer/scan_add.comp");
  // Level 0 scans count + 1 values (the extra one yields the total); each further level
  // scans the block sums of the one before, until a level fits in one block.
  uint64_t values = count + 1;
  for (;;) {
    const uint64_t blocks = groups_for(values, kScanBlock);
    block_sums_.emplace_back("scan_block_sums", blocks * sizeof(uint32_t));
    if (blocks == 1) break;
    values = blocks;
  }
}

uint64_t PrefixSum::scratch_bytes() const {
  uint64_t bytes = 0;
  for (const auto& b : block_sums_) bytes += b.bytes();
  return bytes;
}

void PrefixSum::scan_level(const GlBuffer& input, uint64_t input_count, const GlBuffer& output,
                           uint64_t count, const GlBuffer& block_sums) const {
  const uint64_t groups = groups_for(count, kScanBlock);
  input.bind_storage(kStructureBinding0);
  output.bind_storage(kStructureBinding0 + 1);
  block_sums.bind_storage(kStructureBinding0 + 2);
  scan_program_.use();
  scan_program_.set("scan_input_count", unsigned(input_count));
  scan_program_.set("scan_count", unsigned(count));
  scan_program_.set("scan_group_count", unsigned(groups));
  // Only the counting variant has it (elsewhere a no-op): level 0 reads the counts and writes
  // the offsets, the others scan block sums.
  scan_program_.set("work_scan_level", unsigned(&block_sums == &block_sums_[0] ? 0 : 1));
  dispatch_linear_groups(groups);
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
}

void PrefixSum::add_block_offsets(const GlBuffer& values, uint64_t count,
                                  const GlBuffer& block_offsets) const {
  const uint64_t groups = groups_for(count, kScanBlock);
  values.bind_storage(kStructureBinding0);
  block_offsets.bind_storage(kStructureBinding0 + 1);
  add_program_.use();
  add_program_.set("scan_count", unsigned(count));
  add_program_.set("scan_group_count", unsigned(groups));
  // Only the counting variant has it: level 0 adds to the offsets, the others to block sums.
  add_program_.set("work_scan_level", unsigned(&block_offsets == &block_sums_[0] ? 0 : 1));
  dispatch_linear_groups(groups);
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
}

void PrefixSum::run(const GlBuffer& input, const GlBuffer& output) const {
  // The values each level scans: level 0 the output (count_ inputs and one zero more, so
  // that the total lands at output[count_]), level l the block sums of level l - 1, in place.
  auto values_of = [&](size_t level) -> const GlBuffer& {
    return level == 0 ? output : block_sums_[level - 1];
  };
  std::vector<uint64_t> counts = {count_ + 1};
  scan_level(input, count_, output, counts[0], block_sums_[0]);
  for (size_t level = 1; level < block_sums_.size(); ++level) {
    counts.push_back(groups_for(counts.back(), kScanBlock));
    scan_level(values_of(level), counts[level], values_of(level), counts[level],
               block_sums_[level]);
  }
  // Back up: every block adds the scanned sum of the blocks before it (the uniform add).
  for (size_t level = block_sums_.size() - 1; level-- > 0;)
    add_block_offsets(values_of(level), counts[level], block_sums_[level]);
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
}

}  // namespace ldm
