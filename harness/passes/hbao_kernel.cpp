#include "harness/passes/hbao_kernel.h"

#include "harness/gl/bindings.h"
#include "harness/gl/shader_program.h"
#include "harness/passes/gbuffer_pass.h"
#include "harness/reference/pcg32.h"

namespace ldm {

std::vector<WorkCounter> hbao_blur_work_counters(const std::string& subpass) {
  return {
      {subpass, "fragments", WorkShape::Total, "fragments",
       subpass + ": fragments the separable cross-bilateral blur shaded (a horizontal and a vertical "
                 "full-screen pass: twice the image's pixels)"},
      {subpass, "taps", WorkShape::Total, "taps",
       subpass + ": neighbour taps the blur weighed (inside the image and over a surface; the "
                 "pixel's own is not counted)"},
  };
}
std::vector<WorkCounter> horizon_search_work_counters(const std::string& name,
                                                      const std::string& smoothing,
                                                      const HorizonSearchCounters& own) {
  const std::string what = name + ": ";
  return with_gbuffer_counters(
      {
          {name, "fragments", WorkShape::Total, "fragments",
           what + "fragments the full-screen horizon search shaded (every image pixel)"},
          {name, "covered_pixels", WorkShape::Total, "pixels", what + "image pixels that see a surface (searched)"},
          {name, own.searched, WorkShape::Total, own.searched, what + own.searched_what},
          {name, "samples", WorkShape::Total, "samples", what + own.samples_what},
          {name, "horizon_rises", WorkShape::Total, "samples",
           what + "samples that raised a horizon (the ones that add occlusion)"},
          {name, "steps", WorkShape::Distribution, "samples", what + own.steps_what},
      },
      hbao_blur_work_counters(smoothing));
}

namespace {

// The tiled random table's stream: fixed, so a jittered image is reproducible.
constexpr uint64_t kJitterSeed = 0x4842414fu;  // "HBAO"

void set_camera_uniforms(const GlProgram& p, const HbaoCamera& camera) {
  p.set("camera_eye", camera.eye.x, camera.eye.y, camera.eye.z);
  p.set("camera_forward", camera.forward.x, camera.forward.y, camera.forward.z);
  p.set("focal_pixels", camera.focal_pixels);
}

ShaderDefines hbao_defines(const HbaoSettings& hbao, const AoSettings& ao) {
  ShaderDefines defines = binding_defines();
  defines.set("HBAO_DIRECTIONS", std::to_string(hbao.directions));
  defines.set("HBAO_STEPS", std::to_string(hbao.steps));
  defines.set("HBAO_ATTENUATED", ao.attenuated ? 1 : 0);
  return defines;
}

}  // namespace

HbaoKernel::HbaoKernel(const HbaoSettings& hbao, const AoSettings& ao, int width, int height)
    : FullscreenAoKernel("HBAO", "passes/hbao.frag", hbao_defines(hbao, ao), width, height) {
  program_.set("hbao_radius", ao.d_max);
  program_.set("hbao_falloff_exponent", ao.falloff_exponent);
  program_.set("hbao_angle_bias", hbao.angle_bias);
  const std::array<glm::vec2, 16> table = jitter_table(hbao);
  glProgramUniform2fv(program_.id(), program_.uniform("hbao_jitter"), GLsizei(table.size()),
                      &table[0].x);
  check_gl("HBAO uniforms");
}

std::array<glm::vec2, 16> HbaoKernel::jitter_table(const HbaoSettings& hbao) const {
  std::array<glm::vec2, 16> table;
  Pcg32 rng(kJitterSeed, 1);
  const float rotation_range = 2.0f * 3.14159265f / float(hbao.directions);
  for (glm::vec2& entry : table) {
    if (!hbao.jitter) {
      entry = {0.0f, 1.0f};  // the thesis's fixed directions; samples at 1..S steps
      continue;
    }
    entry.x = rng.next_float() * rotation_range;
    entry.y = 1.0f - rng.next_float();  // (0, 1]: never the pixel itself
  }
  return table;
}

void HbaoKernel::set_camera(const HbaoCamera& camera) { set_camera_uniforms(program_, camera); }

HbaoBlur::HbaoBlur(uint32_t radius, const GlTexture2D& ao)
    : ao_(ao), width_(ao.width()), height_(ao.height()), scratch_(GL_R32F, width_, height_) {
  scratch_framebuffer_.attach_color(0, scratch_);
  scratch_framebuffer_.check_complete("HBAO blur scratch");
  ao_framebuffer_.attach_color(0, ao_);  // the vertical pass writes the AO target again
  ao_framebuffer_.check_complete("HBAO blur output");
  ShaderDefines defines = binding_defines();
  defines.set("HBAO_BLUR_RADIUS", std::to_string(radius));
  program_ = build_program({{GL_VERTEX_SHADER, "passes/fullscreen.vert", {}},
                            {GL_FRAGMENT_SHADER, "passes/hbao_blur.frag", {}}},
                           defines);
}

void HbaoBlur::set_camera(const HbaoCamera& camera) { set_camera_uniforms(program_, camera); }

void HbaoBlur::run_direction(const GlTexture2D& source, const GlFramebuffer& target, int dx,
                             int dy, const GlTexture2D& positions,
                             const GlTexture2D& normals) const {
  glBindTextureUnit(0, positions.id());
  glBindTextureUnit(1, normals.id());
  glBindTextureUnit(2, source.id());
  glProgramUniform2i(program_.id(), program_.uniform("blur_step"), dx, dy);
  draw_fullscreen(target.id(), width_, height_, program_, empty_vao_);
}

void HbaoBlur::run(const GlTexture2D& positions, const GlTexture2D& normals) const {
  run_direction(ao_, scratch_framebuffer_, 1, 0, positions, normals);
  run_direction(scratch_, ao_framebuffer_, 0, 1, positions, normals);
}

}  // namespace ldm
