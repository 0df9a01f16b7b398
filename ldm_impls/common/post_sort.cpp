#include "ldm_impls/common/post_sort.h"
#include "ldm_impls/common/sizing_strategy.h"
#include "ldm_impls/common/structure_counters.h"

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

WorkCounter sort_invocations_counter() {
  return {"sort", "invocations", WorkShape::Total, "invocations",
          "sort: compute invocations of the sort dispatch (one per pixel, the last group's padding "
          "included)"};
}

std::vector<WorkCounter> post_sort_work_counters(const std::vector<WorkCounter>& memory) {
  std::vector<WorkCounter> counters = {
      sort_invocations_counter(),
      {"sort", "list_length", WorkShape::Distribution, "entries",
       "sort: PPSLL or DF-buffer fragments of one pixel's list or range (one value per pixel, "
       "empty ones included)"},
      {"sort", "comparisons", WorkShape::Total, "comparisons",
       "sort: depth comparisons of the sorts (insertion sort in the local array, "
       "ldm/common/post_sort.glsl; PPSLL's merge sort in place; heap sort in place, "
       "ldm/common/heap_sort.glsl)", kArrival},
      {"sort", "moves", WorkShape::Total, "moves",
       "sort: entries the sorts moved (local-array writes of the insertion sort; nodes PPSLL's "
       "merge sort relinked; heap_store calls of the heap sort)", kArrival},
  };
  counters.insert(counters.end(), memory.begin(), memory.end());
  counters.push_back({"sort", "atomic_add", WorkShape::Total, "atomics",
                      "sort: atomic counter increments of lists sorted in place (longer than the "
                      "local array)"});
  return counters;
}

}  // namespace ldm
