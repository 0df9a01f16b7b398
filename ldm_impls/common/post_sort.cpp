#include "ldm_impls/common/post_sort.h"

#include <algorithm>

namespace ldm {

uint32_t read_sort_local_param(StructureParams& params) {
  return uint32_t(params.get_uint("local", 0, 1, kMaxSortLocal));
}

uint32_t sort_local_size(uint32_t requested, const SizingPlan& plan) {
  if (requested != 0) return requested;
  if (plan.policy != SizingPolicy::Oracle) return kDefaultSortLocal;
  return std::clamp<uint32_t>(plan.initial.max_depth_complexity, 1, kMaxSortLocal);
}

std::string sort_local_policy(uint32_t requested, const SizingPlan& plan) {
  if (requested) return "user";
  return plan.policy == SizingPolicy::Oracle ? "oracle_max_depth_complexity" : "default";
}

}  // namespace ldm
