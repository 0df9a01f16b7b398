#pragma once
// The frame of every structure's work_counters(): what its geometry sub-passes count without
// its help (geometry_work_counters(), one set per sub-pass that rasterises the scene), then
// the counters of its own shaders.
#include <initializer_list>
#include <vector>

#include "ldm_impls/ldm_structure.h"

namespace ldm {

inline std::vector<WorkCounter> with_geometry_counters(
    std::initializer_list<const char*> geometry_subpasses, const std::vector<WorkCounter>& own) {
  std::vector<WorkCounter> counters;
  for (const char* subpass : geometry_subpasses)
    for (WorkCounter c : geometry_work_counters(subpass)) counters.push_back(std::move(c));
  counters.insert(counters.end(), own.begin(), own.end());
  return counters;
}

}  // namespace ldm
