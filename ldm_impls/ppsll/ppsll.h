#pragma once
// Per-pixel singly linked lists, post-sorted (thesis §3.2.8, §3.4.1): one geometry pass
// pushes every fragment onto the front of its pixel's list (atomic counter allocation and
// atomicExchange on the head, Listing 2), then a compute pass sorts every list (§3.3.3).
// All views share one data buffer with per-view pixel offsets, laid out like PSPPSLL's, so
// the query is PSPPSLL's (shaders/ldm/psppsll/query.glsl). Shaders: shaders/ldm/ppsll/.
//
// Sub-passes: clear, construct, sort.
// Parameters:
//   pool=counted|grow|fixed
//                       as PSPPSLL: counted (default) holds exactly the census's fragments;
//                       grow starts at one node per LDM pixel and doubles, rebuilding, until
//                       a construction fits (§3.4.4), rebuilds counted; fixed holds exactly
//                       `capacity` nodes (§3.3.4), fragments beyond it counted as lost.
//   capacity=<nodes>    the pool size for pool=fixed.
//   local=K             size of the sort's local array, 1..128 (default: the census's
//                       maximum depth complexity, capped at 128). Longer lists are sorted in
//                       place in storage memory and counted as "lists_sorted_in_place".
#include <memory>

#include "harness/gl/gl_objects.h"
#include "ldm_impls/common/ldm_rasterizer.h"
#include "ldm_impls/ldm_structure.h"

namespace ldm {

class Ppsll final : public LdmStructure {
 public:
  explicit Ppsll(StructureParams& params);

  std::string name() const override { return "ppsll"; }
  void prepare(const BuildInputs& in) override;
  void build(const BuildInputs& in, GpuTimer* timer) override;
  BuildStats stats() override;
  std::vector<std::string> query_sources() const override;
  ShaderDefines query_defines() const override;
  void bind_for_query() const override;
  std::vector<BufferMemory> memory() const override;
  std::vector<std::pair<std::string, std::string>> sizing() const override;

 private:
  void allocate(const BuildInputs& in, uint64_t capacity);
  void construct(const BuildInputs& in, GpuTimer* timer);
  void sort(GpuTimer* timer);
  uint64_t read_node_counter() const;

  enum class Pool { Counted, Grow, Fixed } pool_ = Pool::Counted;
  uint64_t fixed_capacity_ = 0;
  uint32_t requested_local_ = 0;  // 0: from the census
  uint32_t local_ = 0;            // K of the sort pass
  uint64_t heads_ = 0;            // N * R_LDM^2
  uint64_t capacity_ = 0;         // nodes
  uint64_t rebuilds_ = 0;
  uint64_t stored_ = 0;  // nodes held after the last build (from stats())
  ShaderDefines query_defines_;
  GlBuffer data_;
  GlBuffer counters_;  // [0] nodes allocated, [1] lists sorted in place
  GlProgram build_program_, sort_program_;
  std::unique_ptr<LdmRasterizer> rasterizer_;
};

}  // namespace ldm
