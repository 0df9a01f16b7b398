#include "ldm_impls/common/ldm_rasterizer.h"

#include "harness/gl/bindings.h"

namespace ldm {

LdmRasterizer::LdmRasterizer(uint32_t resolution) : resolution_(resolution) {
  framebuffer_.set_default_size(int(resolution), int(resolution));
  framebuffer_.check_complete("LDM rasterizer");
}

void LdmRasterizer::rasterize(const GpuScene& scene, const GpuViewSet& views,
                              const GlProgram& program) const {
  glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_.id());
  glViewport(0, 0, GLsizei(resolution_), GLsizei(resolution_));
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_CULL_FACE);
  glDisable(GL_BLEND);
  glDisable(GL_MULTISAMPLE);
  views.bind();
  program.use();
  const GLint view_uniform = program.uniform("ldm_view_index");
  for (uint32_t v = 0; v < views.views().size(); ++v) {
    glProgramUniform1ui(program.id(), view_uniform, v);
    scene.draw();
  }
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_ATOMIC_COUNTER_BARRIER_BIT |
                  GL_BUFFER_UPDATE_BARRIER_BIT);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

GlProgram build_ldm_raster_program(const std::string& fragment_file, const ShaderDefines& defines) {
  ShaderDefines all = binding_defines();
  all.values.insert(all.values.end(), defines.values.begin(), defines.values.end());
  return build_program({{GL_VERTEX_SHADER, "ldm/ldm_raster.vert", {}},
                        {GL_FRAGMENT_SHADER, fragment_file, {}}},
                       all);
}

}  // namespace ldm
