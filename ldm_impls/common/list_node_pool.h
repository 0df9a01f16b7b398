#pragma once
// The node pool of the linked-list structures, PPSLL and PSPPSLL (thesis §3.3.4, §3.4.4):
// one data buffer with every pixel's head index followed by the nodes
// (shaders/ldm/common/list_nodes.glsl), an atomic counter that allocates nodes, and the
// sizing of the pool. The size follows the sizing policy (ldm_impls/common/sizing.h): the
// plan's fragments (oracle, census, previous_frame; grown by resize() from the node counter
// or the census), or the budget less the heads (budget). The parameter
//   capacity=<nodes>  fixes the pool at that many nodes under every policy (the static
//                     memory budget of §3.3.4 in nodes); fragments beyond it are lost, counted
// overrides the policy. (The former pool=counted|grow|fixed are the policies oracle,
// previous_frame and budget/capacity.) A construction writes no node past the capacity;
// the counter still counts them, so the host knows exactly how many did not fit.
#include <array>
#include <memory>
#include <string>

#include "harness/gl/gl_objects.h"
#include "ldm_impls/common/sizing_strategy.h"
#include "ldm_impls/ldm_structure.h"

namespace ldm {

class ListNodePool {
 public:
  static constexpr uint64_t kWordsPerNode = 2;  // next index, depth

  ListNodePool(const std::string& structure, StructureParams& params);
  // The `capacity` parameter of a structure built on a pool.
  static AxisSpec capacity_parameter();
  // What the list query (shaders/ldm/common/list_query.glsl) counts in a pass's sub-pass
  // (the sub-pass filled in by the caller): PSPPSLL's and PPSLL's query_work_counters().
  static std::vector<WorkCounter> query_work_counters();
  // Their first: the nodes a query moved onto, which the DF-buffer's ranges count alike.
  static WorkCounter nodes_visited_counter();

  // Sizes the pool by the sizing plan and compiles `build_shader` (a fragment shader of the
  // LDM geometry pass) with the pool's defines and `extra_defines`.
  void prepare(const BuildInputs& in, const std::string& build_shader, ShaderDefines extra_defines);
  // The "clear" and "construct" sub-passes.
  void build(const BuildInputs& in, GpuTimer* timer);
  // Sizing (LdmStructure::needed/fits/resize): the node counter counts every allocation
  // attempt, so it says what the pool needed even when it overflowed.
  SizingNeeds needed() const;
  bool fits(const SizingNeeds& needs) const;
  void resize(const SizingNeeds& needs);
  // Binds the data buffer to the structure's first storage binding and the counters.
  void bind() const;

  // The counter words after the last construction: [0] nodes the fragments asked for,
  // [1] the structure's own (PSPPSLL: aborted insertions, PPSLL: lists sorted in place).
  std::array<uint32_t, 2> read_counters() const;
  // Rasterised / stored / lost / overflow of the last build, given how many allocated nodes
  // never made it into a list.
  BuildStats stats(const std::array<uint32_t, 2>& counters, uint64_t unlinked) const;

  uint64_t heads() const { return heads_; }
  // `stored_nodes`: the fragments_stored of stats().
  std::vector<BufferMemory> memory(uint64_t stored_nodes) const;
  std::vector<std::pair<std::string, std::string>> sizing() const;

 private:
  void allocate(uint64_t capacity);
  bool size_is_fixed() const { return fixed_capacity_ > 0 || plan_.strategy().fixed_by_budget(); }

  std::string structure_;
  SizingPlan plan_;
  uint64_t fixed_capacity_ = 0;  // the capacity parameter; 0: the policy sizes the pool
  uint64_t heads_ = 0;     // N * R_LDM^2
  uint64_t capacity_ = 0;  // nodes
  std::string build_shader_;
  ShaderDefines defines_;  // the structure's and the census's, without the capacity
  GlBuffer data_, counters_;
  GlProgram build_program_;
  const FragmentSource* fragments_ = nullptr;  // from prepare(), for recompiles on resize
};

}  // namespace ldm
