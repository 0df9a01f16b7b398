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
// stays is the table form itself. The memory rows, one form for every buffer of every
// structure, are written by bytes_loaded() and bytes_stored().
#include <initializer_list>
#include <string>
#include <vector>

#include "ldm_impls/ldm_structure.h"

namespace ldm {

// The mark of a row whose count depends on the order the fragments arrive in (which entry an
// atomic finds first), short for the tables' rows.
inline constexpr WorkOrder kArrival = WorkOrder::ArrivalDependent;

// The bytes a sub-pass's shaders read (bytes_loaded_<buffer>) or wrote (bytes_stored_<buffer>)
// of one buffer: a total in bytes, described by `what` after the sub-pass's "<subpass>: " (a
// query's counters, sub-pass "", are filled in by their pass and have no prefix).
inline WorkCounter buffer_bytes_counter(const std::string& subpass, const std::string& access,
                                        const std::string& buffer, const std::string& what,
                                        WorkOrder order) {
  return {subpass, "bytes_" + access + "_" + buffer, WorkShape::Total, "bytes",
          subpass.empty() ? what : subpass + ": " + what, order};
}
inline WorkCounter bytes_loaded(const std::string& subpass, const std::string& buffer,
                                const std::string& what,
                                WorkOrder order = WorkOrder::Deterministic) {
  return buffer_bytes_counter(subpass, "loaded", buffer, what, order);
}
inline WorkCounter bytes_stored(const std::string& subpass, const std::string& buffer,
                                const std::string& what,
                                WorkOrder order = WorkOrder::Deterministic) {
  return buffer_bytes_counter(subpass, "stored", buffer, what, order);
}

inline std::vector<WorkCounter> with_geometry_counters(
    std::initializer_list<const char*> geometry_subpasses, const std::vector<WorkCounter>& own) {
  std::vector<WorkCounter> counters;
  for (const char* subpass : geometry_subpasses)
    for (WorkCounter c : geometry_work_counters(subpass)) counters.push_back(std::move(c));
  counters.insert(counters.end(), own.begin(), own.end());
  return counters;
}

}  // namespace ldm
