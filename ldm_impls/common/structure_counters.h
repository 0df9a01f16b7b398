#pragma once
// The frame of every structure's work_counters(): what its geometry sub-passes count without
// its help (geometry_work_counters(), one set per sub-pass that rasterises the scene), then
// the counters of its own shaders.
//
// The own counters are a data table, one row a counter ({sub-pass, name, shape, unit,
// description[, order]}), declared beside the shaders that count them. The tables of the
// structures and passes look alike to a duplicate finder (same shape of row) but share no
// rows: each row that two of them did share is declared once (post_sort_work_counters(),
// sort_invocations_counter(), ListNodePool::nodes_visited_counter()), so the likeness that
// stays is the table form itself.
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
