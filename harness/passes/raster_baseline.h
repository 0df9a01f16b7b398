#pragma once
// The cost floor of every structure's construction: the same LDM views rasterised with the
// same geometry pass but a fragment shader that stores nothing. Records report each
// structure's construction time also as a ratio to it.
#include "harness/measure/gpu_timer.h"
#include "ldm_impls/common/ldm_rasterizer.h"

namespace ldm {

class RasterBaseline {
 public:
  explicit RasterBaseline(uint32_t resolution);
  void render(const GpuScene& scene, const GpuViewSet& views, GpuTimer* timer) const;

 private:
  LdmRasterizer rasterizer_;
  GlProgram program_;
};

}  // namespace ldm
