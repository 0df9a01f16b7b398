#pragma once
// Post-sorting, shared by PPSLL and the DF-buffer (thesis §3.2.8 "Sorting", §3.3.3): a pass
// over every pixel copies its fragments into a shader-local array of fixed size K, sorts it
// with insertion sort and writes the depths back in order. A pixel with more than K
// fragments is sorted in place in storage memory instead (PPSLL: merge sort relinking the
// nodes; DF-buffer: heap sort, shaders/ldm/common/heap_sort.glsl), which §3.3.3 calls
// detrimental to performance; the sort passes count those pixels ("lists_sorted_in_place").
// GLSL side: shaders/ldm/common/post_sort.glsl.
#include <cstdint>
#include <string>
#include <vector>

#include "ldm_impls/ldm_structure.h"

namespace ldm {

// Upper bound on K: every invocation holds K floats, so a larger K costs registers (or
// spills) in every pixel, long or short. Longer lists take the in-place path.
constexpr uint32_t kMaxSortLocal = 128;

// The `local` parameter: K, in [1, kMaxSortLocal]; 0 when the user left it unset.
AxisSpec sort_local_parameter();
uint32_t read_sort_local_param(const StructureParams& params);

// K when neither the parameter nor the oracle sets it: a compile-time constant, as in a
// renderer that does not know the scene's depth complexity; deeper lists are sorted in
// place (counted).
constexpr uint32_t kDefaultSortLocal = 64;

// K: the requested size; else, under the oracle policy, the census's maximum depth
// complexity (model only what the scene requires) capped at kMaxSortLocal, at least 1;
// else kDefaultSortLocal.
uint32_t sort_local_size(uint32_t requested, const SizingPlan& plan);

// For sizing(): "user", "oracle_max_depth_complexity" or "default".
std::string sort_local_policy(uint32_t requested, const SizingPlan& plan);

// The sort sub-pass's compute invocations, one per pixel (also PPFLA's heap sort's).
WorkCounter sort_invocations_counter();
// The sort sub-pass's counters, as PPSLL and the DF-buffer declare them: its invocations, the
// lists' lengths, the sorts' comparisons and moves, then `memory` (the structure's own loads
// and stores), then the atomic counter increments of lists sorted in place.
std::vector<WorkCounter> post_sort_work_counters(const std::vector<WorkCounter>& memory);

}  // namespace ldm
