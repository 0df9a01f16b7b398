#pragma once
// Pre-sorted per-pixel singly linked lists (thesis §3.2.14, §3.4.2): one geometry pass that
// inserts every fragment into its pixel's list in depth order with atomicCompSwap; all views
// in one data buffer (§3.4.4). Shaders: shaders/ldm/psppsll/.
//
// Parameters:
//   pool=counted|grow|fixed
//                       counted (default): the node pool holds exactly the census's fragments.
//                       grow: starts at one node per LDM pixel and doubles, rebuilding, until
//                       a build fits (the std::vector policy of §3.4.4); rebuilds are counted.
//                       fixed: exactly `capacity` nodes, the static memory budget of §3.3.4;
//                       fragments beyond it are counted as lost and the record says so.
//   capacity=<nodes>    the pool size for pool=fixed.
//   atomic_reads=0|1    read next indices with atomicAdd(x, 0), the driver workaround of
//                       §3.4.3 (default 0).
#include <memory>

#include "harness/gl/gl_objects.h"
#include "ldm_impls/common/ldm_rasterizer.h"
#include "ldm_impls/ldm_structure.h"

namespace ldm {

class Psppsll final : public LdmStructure {
 public:
  explicit Psppsll(StructureParams& params);

  std::string name() const override { return "psppsll"; }
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
  uint64_t read_node_counter() const;

  enum class Pool { Counted, Grow, Fixed } pool_ = Pool::Counted;
  uint64_t fixed_capacity_ = 0;
  bool atomic_reads_ = false;
  uint64_t heads_ = 0;     // N * R_LDM^2
  uint64_t capacity_ = 0;  // nodes
  uint64_t rebuilds_ = 0;
  uint64_t stored_ = 0;  // nodes held after the last build (from stats())
  ShaderDefines query_defines_;
  GlBuffer data_, counters_;
  GlProgram build_program_;
  std::unique_ptr<LdmRasterizer> rasterizer_;
};

}  // namespace ldm
