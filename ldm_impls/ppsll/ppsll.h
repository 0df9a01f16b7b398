#pragma once
// Per-pixel singly linked lists, post-sorted (thesis §3.2.8, §3.4.1): one geometry pass
// pushes every fragment onto the front of its pixel's list (atomic counter allocation and
// atomicExchange on the head, Listing 2), then a compute pass sorts every list (§3.3.3).
// All views share one data buffer with per-view pixel offsets, laid out like PSPPSLL's, so
// the query is the lists' (shaders/ldm/common/list_query.glsl). Shaders: shaders/ldm/ppsll/.
//
// Sub-passes: clear, construct, sort.
// Parameters:
//   capacity=<nodes>    fixes the node pool (common/list_node_pool.h); else the sizing policy
//   local=K             size of the sort's local array, 1..128 (default: under the oracle
//                       policy the census's maximum depth complexity capped at 128, else
//                       kDefaultSortLocal = 64). Longer lists are merge-sorted in place by
//                       relinking their nodes and counted as "lists_sorted_in_place".
#include "ldm_impls/common/list_node_pool.h"

namespace ldm {

class Ppsll final : public LdmStructure {
 public:
  explicit Ppsll(StructureParams& params);
  // The parameters --param ppsll:KEY=VALUE sets, declared (harness/axes/axis.h).
  static std::vector<AxisSpec> parameters();
  // What its build counts in the counting replay (harness/measure/work_counters.h).
  static std::vector<WorkCounter> work_counters();
  // What its query code counts in a pass's sub-pass (filled in by the caller).
  static std::vector<WorkCounter> query_work_counters();

  std::string name() const override { return "ppsll"; }
  void prepare(const BuildInputs& in) override;
  void build(const BuildInputs& in, GpuTimer* timer) override;
  BuildStats stats() const override;
  SizingNeeds needed() override;
  bool fits(const SizingNeeds& needs) const override;
  void resize(const SizingNeeds& needs) override;
  std::vector<std::string> query_sources() const override;
  ShaderDefines query_defines() const override;
  void bind_for_query() const override;
  std::vector<BufferMemory> memory() const override;
  std::vector<std::pair<std::string, std::string>> sizing() const override;

 private:
  void sort(GpuTimer* timer);

  ListNodePool pool_;
  SizingPlan plan_;
  uint32_t requested_local_ = 0;  // 0: from the policy
  uint32_t local_ = 0;            // K of the sort pass
  ShaderDefines query_defines_;
  GlProgram sort_program_;
};

}  // namespace ldm
