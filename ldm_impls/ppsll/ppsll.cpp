#include "ldm_impls/ppsll/ppsll.h"

#include "harness/gl/bindings.h"
#include "ldm_impls/common/compute_grid.h"
#include "ldm_impls/common/post_sort.h"

namespace ldm {

namespace {
constexpr uint64_t kSortGroupSize = 64;  // local_size_x of sort.comp
}  // namespace

Ppsll::Ppsll(StructureParams& params) : pool_("ppsll", params) {
  requested_local_ = read_sort_local_param(params);
}

std::vector<WorkCounter> Ppsll::work_counters() {
  std::vector<WorkCounter> counters;
  for (WorkCounter c : geometry_work_counters("construct")) counters.push_back(std::move(c));
  return counters;
}

std::vector<WorkCounter> Ppsll::query_work_counters() { return {}; }

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
  sort_program_.use();
  dispatch_linear_groups(groups_for(pool_.heads(), kSortGroupSize));
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_ATOMIC_COUNTER_BARRIER_BIT |
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
