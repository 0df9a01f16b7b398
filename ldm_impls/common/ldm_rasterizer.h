#pragma once
#include <cstdint>

#include "harness/gl/gl_objects.h"
#include "harness/gl/shader_program.h"
#include "harness/scene/gpu_scene.h"
#include "harness/views/view_set.h"

namespace ldm {

// The geometry pass every structure's construction shares: the scene drawn once per LDM view
// into an R_LDM x R_LDM framebuffer with no attachments, front and back faces, no depth test
// (every fragment reaches the fragment shader, which writes to storage buffers).
class LdmRasterizer {
 public:
  explicit LdmRasterizer(uint32_t resolution);
  // `program` must use shaders/ldm/ldm_raster.vert (uniform ldm_view_index). Ends with a
  // storage/atomic-counter barrier so later passes see every write.
  void rasterize(const GpuScene& scene, const GpuViewSet& views, const GlProgram& program) const;

 private:
  uint32_t resolution_;
  GlFramebuffer framebuffer_;
};

// A program of ldm_raster.vert with the given fragment shader.
GlProgram build_ldm_raster_program(const std::string& fragment_file, const ShaderDefines& defines);

}  // namespace ldm
