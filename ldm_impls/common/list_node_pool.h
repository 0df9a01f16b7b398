#pragma once
// The node pool of the linked-list structures, PPSLL and PSPPSLL (thesis §3.3.4, §3.4.4):
// one data buffer with every pixel's head index followed by the nodes
// (shaders/ldm/common/list_nodes.glsl), an atomic counter that allocates nodes, and the
// policy that sizes the pool. Parameters, read from the structure's:
//   pool=counted   (default) exactly the census's fragments: nothing wasted, nothing lost
//   pool=grow      one node per LDM pixel to start, doubled and rebuilt until a
//                  construction fits (the std::vector policy of §3.4.4); rebuilds counted
//   pool=fixed     exactly `capacity` nodes, the static memory budget of §3.3.4; fragments
//                  beyond it are counted as lost and the record says so
//   capacity=<nodes>  the size for pool=fixed
// A construction writes no node past the capacity; the counter still counts them, so the
// host knows exactly how many did not fit.
#include <array>
#include <memory>
#include <string>

#include "harness/gl/gl_objects.h"
#include "ldm_impls/ldm_structure.h"

namespace ldm {

class ListNodePool {
 public:
  static constexpr uint64_t kWordsPerNode = 2;  // next index, depth

  ListNodePool(const std::string& structure, StructureParams& params);

  // Sizes the pool by its policy and compiles `build_shader` (a fragment shader of the LDM
  // geometry pass) with the pool's defines and `extra_defines`.
  void prepare(const BuildInputs& in, const std::string& build_shader, ShaderDefines extra_defines);
  // The "clear" and "construct" sub-passes; under pool=grow, repeated with a larger pool
  // until every fragment fitted.
  void build(const BuildInputs& in, GpuTimer* timer);
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
  enum class Policy { Counted, Grow, Fixed };
  void allocate(const BuildInputs& in, uint64_t capacity);
  void construct(const BuildInputs& in, GpuTimer* timer);

  std::string structure_;
  Policy policy_ = Policy::Counted;
  uint64_t fixed_capacity_ = 0;
  uint64_t heads_ = 0;     // N * R_LDM^2
  uint64_t capacity_ = 0;  // nodes
  uint64_t rebuilds_ = 0;
  std::string build_shader_;
  ShaderDefines defines_;  // the structure's and the census's, without the capacity
  GlBuffer data_, counters_;
  GlProgram build_program_;
};

}  // namespace ldm
