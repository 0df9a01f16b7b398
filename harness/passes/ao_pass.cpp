#include "harness/passes/ao_pass.h"

#include "harness/gl/bindings.h"
#include "harness/passes/ldm_trace_defines.h"

namespace ldm {

AoPass::AoPass(const LdmStructure& structure, const BuildInputs& in, int width, int height,
               const AoSettings& settings)
    : structure_(structure),
      views_(in.views),
      width_(width),
      height_(height),
      settings_(settings),
      output_(GL_R32F, width, height),
      steps_(uint32_t(in.views.views().size()), trace_walk_sites(settings.trace == AoTrace::Plane), 0) {
  framebuffer_.attach_color(0, output_);
  framebuffer_.check_complete("AO output");
  compile();
}

// Again whenever the structure's storage changed its query defines (a sizing policy grew
// it): untimed, as a pass of a renderer with run-time sizes would not recompile.
void AoPass::compile() {
  const LdmStructure& structure = structure_;
  const AoSettings& settings = settings_;
  generation_ = structure.storage_generation();
  ShaderDefines defines = binding_defines();
  add_ldm_trace_defines(defines, structure, views_.views().size(), settings.trace);
  defines.set("AO_ATTENUATED", settings.attenuated ? 1 : 0);
  defines.set("AO_NORMALIZED", settings.estimator == AoEstimatorChoice::Normalized ? 1 : 0);
  program_ = build_program({{GL_VERTEX_SHADER, "passes/fullscreen.vert", {}},
                            {GL_FRAGMENT_SHADER, "passes/ao.frag", structure.query_sources()}},
                           defines);
  program_.set("ao_d_max", settings.d_max);
  program_.set("ao_falloff_exponent", settings.falloff_exponent);
  program_.set("ao_normal_offset_pixels", settings.normal_offset_pixels);
}

void AoPass::render(const GBufferPass& gbuffer, GpuTimer* timer) {
  if (structure_.storage_generation() != generation_) compile();
  ScopedSubpass timed(timer, "ao");
  glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_.id());
  glViewport(0, 0, width_, height_);
  glDisable(GL_DEPTH_TEST);
  glBindTextureUnit(0, gbuffer.positions().id());
  glBindTextureUnit(1, gbuffer.normals().id());
  structure_.bind_for_query();
  views_.bind();
  steps_.bind();
  program_.use();
  glBindVertexArray(empty_vao_.id());
  glDrawArrays(GL_TRIANGLES, 0, 3);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

Image AoPass::read_image() const {
  return image_from_gl_rows(output_.read_floats(1), width_, height_, 1);
}

}  // namespace ldm
