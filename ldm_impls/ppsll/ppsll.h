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
  LDM_STRUCTURE_DECLARATIONS("ppsll");

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
