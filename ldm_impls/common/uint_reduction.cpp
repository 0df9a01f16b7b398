#include "ldm_impls/common/uint_reduction.h"

#include "harness/gl/bindings.h"
#include "ldm_impls/common/compute_grid.h"

namespace ldm {

namespace {
constexpr uint64_t kReductionGroupSize = 256;  // local_size_x of reduce_uint.comp
constexpr uint64_t kItemsPerInvocation = 32;
}  // namespace

UintReduction::UintReduction()
    : program_(build_compute_program(
          "ldm/common/reduce_uint.comp",
          ShaderDefines().set("REDUCE_ITEMS_PER_INVOCATION", std::to_string(kItemsPerInvocation) + "u"))),
      result_("reduction", 3 * sizeof(uint32_t)) {}

UintReductionResult UintReduction::run(const GlBuffer& buffer, uint64_t items,
                                       uint32_t words_per_item, uint32_t empty) const {
  result_.clear_to_zero();
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_ATOMIC_COUNTER_BARRIER_BIT);
  buffer.bind_storage(kCensusBinding);
  result_.bind_storage(kValidationBinding);
  program_.use();
  program_.set("reduce_items", unsigned(items));
  program_.set("reduce_words_per_item", unsigned(words_per_item));
  program_.set("reduce_empty", unsigned(empty));
  dispatch_linear_groups(groups_for(items, kReductionGroupSize * kItemsPerInvocation));
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  uint32_t words[3] = {};
  result_.download(words, sizeof words);
  return {words[0], words[1], words[2]};
}

}  // namespace ldm
