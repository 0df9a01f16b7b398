#include "ldm_impls/common/post_sort.h"

#include <algorithm>

namespace ldm {

uint32_t read_sort_local_param(StructureParams& params) {
  return uint32_t(params.get_uint("local", 0, 1, kMaxSortLocal));
}

uint32_t sort_local_size(uint32_t requested, const FragmentCensus& census) {
  if (requested != 0) return requested;
  return std::clamp<uint32_t>(census.max_depth_complexity, 1, kMaxSortLocal);
}

std::string sort_local_policy(uint32_t requested) { return requested ? "user" : "census"; }

}  // namespace ldm
