#include "ldm_impls/common/ldm_rasterizer.h"

#include "harness/gl/bindings.h"

namespace ldm {

LdmRasterizer::LdmRasterizer(uint32_t resolution) : resolution_(resolution) {
  framebuffer_.set_default_size(int(resolution), int(resolution));
  framebuffer_.check_complete("LDM rasterizer");
}

void LdmRasterizer::rasterize(const GpuScene& scene, const GpuViewSet& views,
                              const GlProgram& program, const BlendedWorkTargets* blended) const {
  glDisable(GL_BLEND);
  if (blended)
    blended->begin();
  else
    glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_.id());
  glViewport(0, 0, GLsizei(resolution_), GLsizei(resolution_));
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_CULL_FACE);
  glDisable(GL_MULTISAMPLE);
  views.bind();
  program.use();
  // One draw call for all views: per-view draws and uniform updates would dominate the pass
  // on a GPU for a scene of a few dozen triangles.
  scene.draw_instanced(views.views().size());
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_ATOMIC_COUNTER_BARRIER_BIT |
                  GL_BUFFER_UPDATE_BARRIER_BIT);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  if (blended) blended->end_and_sum();
}

GlProgram build_ldm_raster_program(const std::string& fragment_file, const ShaderDefines& defines) {
  ShaderDefines all = binding_defines();
  all.values.insert(all.values.end(), defines.values.begin(), defines.values.end());
  return build_program({{GL_VERTEX_SHADER, "ldm/ldm_raster.vert", {}},
                        {GL_FRAGMENT_SHADER, fragment_file, {}}},
                       all);
}

RasterFragmentSource::RasterFragmentSource(const GpuScene& scene, const GpuViewSet& views)
    : scene_(scene), views_(views), rasterizer_(views.views().resolution) {}

GlProgram RasterFragmentSource::build_program(const std::string& fragment_file,
                                              const ShaderDefines& defines) const {
  const uint32_t resolution = views_.views().resolution;
  ShaderDefines all = binding_defines();
  all.values.insert(all.values.end(), defines.values.begin(), defines.values.end());
  BlendedTotals totals = blended_totals_of(fragment_file, all, resolution);
  if (totals.empty()) {
    GlProgram program = build_ldm_raster_program(fragment_file, defines);
    blended_.erase(program.id());
    return program;
  }
  ShaderDefines blending = defines;
  const ShaderDefines channels = blend_defines(totals);
  blending.values.insert(blending.values.end(), channels.values.begin(), channels.values.end());
  GlProgram program = build_ldm_raster_program(fragment_file, blending);
  blended_[program.id()] = std::make_unique<BlendedWorkTargets>(resolution, std::move(totals));
  return program;
}

void RasterFragmentSource::run(const GlProgram& program) const {
  const auto blended = blended_.find(program.id());
  rasterizer_.rasterize(scene_, views_, program, blended == blended_.end() ? nullptr : blended->second.get());
}

}  // namespace ldm
