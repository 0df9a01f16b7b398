#include "ldm_impls/ppsll/ppsll.h"

#include "harness/gl/bindings.h"
#include "ldm_impls/common/compute_grid.h"
#include "ldm_impls/common/post_sort.h"
#include "ldm_impls/common/structure_counters.h"

namespace ldm {

namespace {
constexpr uint64_t kSortGroupSize = 64;  // local_size_x of sort.comp
}  // namespace

Ppsll::Ppsll(StructureParams& params) : pool_("ppsll", params) {
  requested_local_ = read_sort_local_param(params);
}

// A data table of its own counters, alike in form only to the other structures' (see
// ldm_impls/common/structure_counters.h).
std::vector<WorkCounter> Ppsll::work_counters() {
  std::vector<WorkCounter> own = {
      // shaders/ldm/ppsll/build.frag: every fragment allocates, stores and pushes one node.
      {"construct", "atomic_add", WorkShape::Total, "atomics",
       "construct: atomic counter increments (PSPPSLL, PPSLL: one node allocation per fragment, "
       "and PSPPSLL's abandoned insertions)"},
      {"construct", "atomic_exchange", WorkShape::Total, "atomics",
       "construct: PPSLL atomicExchange on a list head (one per fragment stored)"},
      bytes_stored("construct", "nodes",
          "PSPPSLL or PPSLL node bytes written: each new node's depth and its next "
          "index (8 bytes per fragment stored; PSPPSLL's rewrites after a lost compare-and-swap "
          "apart)"),
  };
  // shaders/ldm/ppsll/sort.comp with ldm/common/post_sort.glsl: which nodes it reads and
  // writes depends only on the lists' lengths; how many comparisons and moves it needs
  // depends on the order the fragments were pushed in.
  const std::vector<WorkCounter> sort = post_sort_work_counters({
      bytes_loaded("sort", "heads", "PPSLL list heads read (4 bytes per pixel)"),
      bytes_stored("sort", "heads",
          "PPSLL list heads rewritten by the merge sort in place (4 bytes per list longer than local)"),
      bytes_loaded("sort", "nodes",
          "PPSLL node bytes read at every site but the merge sort's comparisons: the copy "
          "into the local array, the write-back's walk, the merge sort's walks (4 bytes per depth "
          "or next index)"),
      bytes_stored("sort", "nodes",
          "PPSLL node bytes written: depths written back, next indices the merge sort relinked"),
      bytes_loaded("sort", "nodes_compared",
          "PPSLL depths the merge sort in place read to compare (4 bytes each)", WorkOrder::ArrivalDependent),
  });
  own.insert(own.end(), sort.begin(), sort.end());
  return with_geometry_counters({"construct"}, own);
}

std::vector<WorkCounter> Ppsll::query_work_counters() { return ListNodePool::query_work_counters(); }

std::vector<AxisSpec> Ppsll::parameters() { return {ListNodePool::capacity_parameter(), sort_local_parameter()}; }

void Ppsll::prepare(const BuildInputs& in) {
  plan_ = in.sizing;
  local_ = sort_local_size(requested_local_, plan_);
  query_defines_ = common_structure_defines(in);
  ShaderDefines sort_defines = common_structure_defines(in);
  sort_defines.set("LDM_SORT_LOCAL", std::to_string(local_) + "u");
  sort_program_ = build_compute_program("ldm/ppsll/sort.comp", sort_defines);
  pool_.prepare(in, "ldm/ppsll/build.frag", {});
}

void Ppsll::sort(GpuTimer* timer) {
  ScopedSubpass timed(timer, "sort");
  pool_.bind();
  run_linear_compute(sort_program_, pool_.heads(), kSortGroupSize,
                     GL_SHADER_STORAGE_BARRIER_BIT | GL_ATOMIC_COUNTER_BARRIER_BIT |
                         GL_BUFFER_UPDATE_BARRIER_BIT);
}

void Ppsll::build(const BuildInputs& in, GpuTimer* timer) {
  pool_.build(in, timer);
  sort(timer);
}

SizingNeeds Ppsll::needed() { return pool_.needed(); }
bool Ppsll::fits(const SizingNeeds& needs) const { return pool_.fits(needs); }
void Ppsll::resize(const SizingNeeds& needs) { pool_.resize(needs); }

BuildStats Ppsll::stats() const {
  const auto counters = pool_.read_counters();  // [1]: lists the sort did in place
  BuildStats s = pool_.stats(counters, 0);
  s.counters.emplace_back("lists_sorted_in_place", double(counters[1]));
  return s;
}

// Sorted after construction, the lists answer queries like PSPPSLL's.
std::vector<std::string> Ppsll::query_sources() const { return {"ldm/common/list_query.glsl"}; }
ShaderDefines Ppsll::query_defines() const { return query_defines_; }
void Ppsll::bind_for_query() const { pool_.bind(); }
std::vector<BufferMemory> Ppsll::memory() const { return pool_.memory(stats().fragments_stored); }

std::vector<std::pair<std::string, std::string>> Ppsll::sizing() const {
  auto s = pool_.sizing();
  s.emplace_back("sort_local", std::to_string(local_));
  s.emplace_back("sort_local_policy", sort_local_policy(requested_local_, plan_));
  return s;
}

}  // namespace ldm
