#include "ldm_impls/common/post_sort.h"
#include "ldm_impls/common/sizing_strategy.h"

#include <algorithm>

namespace ldm {

AxisSpec sort_local_parameter() {
  AxisSpec p = numeric_parameter(
      "local", AxisKind::UInt, 1, kMaxSortLocal, "", "entries",
      "entries of the sort pass's local array (longer lists are merge-sorted in place)");
  p.default_note = "oracle: the census's deepest pixel (at most 128); other policies: 64";
  return p;
}

uint32_t read_sort_local_param(const StructureParams& params) {
  return params.has("local") ? uint32_t(params.get_uint("local")) : 0;
}

uint32_t sort_local_size(uint32_t requested, const SizingPlan& plan) {
  if (requested != 0) return requested;
  if (!plan.strategy().sized_by_oracle()) return kDefaultSortLocal;
  return std::clamp<uint32_t>(plan.initial.max_depth_complexity, 1, kMaxSortLocal);
}

std::string sort_local_policy(uint32_t requested, const SizingPlan& plan) {
  if (requested) return "user";
  return plan.strategy().sized_by_oracle() ? "oracle_max_depth_complexity" : "default";
}

}  // namespace ldm
