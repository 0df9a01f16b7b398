#pragma once
// Pre-sorted per-pixel singly linked lists (thesis §3.2.14, §3.4.2): one geometry pass that
// inserts every fragment into its pixel's list in depth order with atomicCompSwap; all views
// in one data buffer (§3.4.4). Shaders: shaders/ldm/psppsll/build.frag and the list query
// shaders/ldm/common/list_query.glsl.
//
// Sub-passes: clear, construct.
// Parameters:
//   capacity=<nodes>    fixes the node pool (common/list_node_pool.h); else the sizing policy
//   atomic_reads=0|1    read next indices with atomicAdd(x, 0), the driver workaround of
//                       §3.4.3 (default 0)
#include <optional>
#include <string>

#include "harness/gl/driver_probe.h"
#include "ldm_impls/common/list_node_pool.h"

namespace ldm {

// Why PSPPSLL's build cannot run on a driver whose self-test failed the barrier its insertion
// loop depends on (memoryBarrier() in a divergent loop) in `stage`; nullopt when it can.
std::optional<std::string> psppsll_driver_refusal(const DriverConformance& driver,
                                                  ProbeStage stage);

class Psppsll final : public LdmStructure {
 public:
  explicit Psppsll(StructureParams& params);
  LDM_STRUCTURE_DECLARATIONS("psppsll");

 private:
  ListNodePool pool_;
  bool atomic_reads_ = false;
  ShaderDefines query_defines_;
};

}  // namespace ldm
