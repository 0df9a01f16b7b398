#pragma once
#include <cstdint>
#include <map>
#include <memory>

#include "harness/gl/gl_objects.h"
#include "harness/gl/shader_program.h"
#include "harness/scene/gpu_scene.h"
#include "harness/views/view_set.h"
#include "ldm_impls/common/blended_work_counts.h"
#include "ldm_impls/common/fragment_source.h"

namespace ldm {

// The geometry pass every structure's construction shares: the scene drawn into every LDM
// view, all views in one instanced draw call (instance i is view i; the views share the
// R_LDM x R_LDM viewport), into a framebuffer with no attachments, front and back faces, no
// depth test (every fragment reaches the fragment shader, which writes to storage buffers).
class LdmRasterizer {
 public:
  explicit LdmRasterizer(uint32_t resolution);
  // `program` must use shaders/ldm/ldm_raster.vert (build_ldm_raster_program). Ends with a
  // storage/atomic-counter barrier so later passes see every write. With `blended` (a
  // counting variant that counts its totals by blending), draws into its targets and sums
  // them after the draw.
  void rasterize(const GpuScene& scene, const GpuViewSet& views, const GlProgram& program,
                 const BlendedWorkTargets* blended = nullptr) const;

 private:
  uint32_t resolution_;
  GlFramebuffer framebuffer_;
};

// A program of ldm_raster.vert with the given fragment shader.
GlProgram build_ldm_raster_program(const std::string& fragment_file, const ShaderDefines& defines);

// The fragments of `scene` in every view of `views`: the source ldmbench measures. Both must
// outlive it.
class RasterFragmentSource : public FragmentSource {
 public:
  RasterFragmentSource(const GpuScene& scene, const GpuViewSet& views);
  GlProgram build_program(const std::string& fragment_file,
                          const ShaderDefines& defines) const override;
  void run(const GlProgram& program) const override;
  ProbeStage stage() const override { return ProbeStage::Fragment; }

 private:
  const GpuScene& scene_;
  const GpuViewSet& views_;
  LdmRasterizer rasterizer_;
  // The counting variants built here that count their totals by blending, by program name:
  // every program run() is given was built here, which sets (or erases) its entry, so a
  // name the driver reuses never finds another program's targets.
  mutable std::map<GLuint, std::unique_ptr<BlendedWorkTargets>> blended_;
};

}  // namespace ldm
