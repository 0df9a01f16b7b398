#include "harness/passes/raster_baseline.h"

namespace ldm {

RasterBaseline::RasterBaseline(uint32_t resolution)
    : rasterizer_(resolution), program_(build_ldm_raster_program("ldm/raster_only.frag", {})) {}

void RasterBaseline::render(const GpuScene& scene, const GpuViewSet& views,
                            GpuTimer* timer) const {
  ScopedSubpass timed(timer, "raster_baseline");
  rasterizer_.rasterize(scene, views, program_);
}

}  // namespace ldm
