#include "harness/passes/hbao.h"

#include <cmath>

#include "harness/gl/bindings.h"
#include "harness/gl/gl_objects.h"
#include "harness/metrics/ao_range.h"
#include "harness/reference/ao_reference.h"
#include "harness/reference/pcg32.h"
#include "harness/reference/reference_settings.h"
#include "harness/scene/camera.h"
#include "harness/util/error.h"

namespace ldm {
namespace {

// The tiled random table's stream: fixed, so a jittered image is reproducible.
constexpr uint64_t kJitterSeed = 0x4842414fu;  // "HBAO"

}  // namespace

struct Hbao::Gpu {
  GlTexture2D output;
  GlFramebuffer framebuffer;
  GlVertexArray empty_vao;
  GlProgram program;
};

Hbao::Hbao(StructureParams& params) {
  hbao_.directions = uint32_t(params.get_uint("directions", hbao_.directions, 1, 256));
  hbao_.steps = uint32_t(params.get_uint("steps", hbao_.steps, 1, 512));
  hbao_.angle_bias = float(params.get_double("angle_bias", hbao_.angle_bias, 0.0, 1.5));
  hbao_.jitter = params.get_choice("jitter", "off", {"off", "on"}) == "on";
  // An absent key keeps the scene's value, as for the LDM AO.
  if (params.has("d_max")) overrides_.d_max = float(params.get_double("d_max", 0.0, 1e-30, 1e30));
  const std::string visibility =
      params.get_choice("visibility", "scene", {"scene", "attenuated", "unattenuated"});
  if (visibility != "scene") overrides_.attenuated = visibility == "attenuated";
}

Hbao::~Hbao() = default;

AoSettings Hbao::settings_for(const Scene& scene) const {
  return apply_ao_overrides(scene.ao, overrides_);
}

PassRequirements Hbao::requirements() const {
  PassRequirements r;
  r.scene_attributes.normals = true;  // the G-buffer pass draws them (HBAO reads positions)
  r.needs_structure = false;
  return r;
}

std::vector<TimedSubpass> Hbao::subpasses() const {
  return {{"gbuffer", "G-buffer: world positions and camera-facing normals from the camera"},
          {"hbao", "HBAO: horizon search in the G-buffer, N_HBAO x S_HBAO samples per pixel"}};
}

std::vector<std::pair<std::string, RecordValue>> Hbao::describe(const Scene& scene) const {
  const AoSettings ao = settings_for(scene);
  return {{"visibility", std::string(ao.attenuated ? "attenuated" : "unattenuated")},
          {"d_max", double(ao.d_max)},
          {"hbao_directions", int64_t(hbao_.directions)},
          {"hbao_steps", int64_t(hbao_.steps)},
          {"hbao_angle_bias", double(hbao_.angle_bias)},
          {"hbao_jitter", std::string(hbao_.jitter ? "on" : "off")}};
}

std::array<glm::vec2, 16> Hbao::jitter_table() const {
  std::array<glm::vec2, 16> table;
  Pcg32 rng(kJitterSeed, 1);
  const float rotation_range = 2.0f * 3.14159265f / float(hbao_.directions);
  for (glm::vec2& entry : table) {
    if (!hbao_.jitter) {
      entry = {0.0f, 1.0f};  // the thesis's fixed directions; samples at 1..S steps
      continue;
    }
    entry.x = rng.next_float() * rotation_range;
    entry.y = 1.0f - rng.next_float();  // (0, 1]: never the pixel itself
  }
  return table;
}

void Hbao::prepare(const PassInputs& in) {
  scene_ = &in.scene;
  gpu_scene_ = &in.gpu_scene;
  width_ = in.width;
  height_ = in.height;
  gbuffer_ = std::make_unique<GBufferPass>(in.width, in.height);
  gpu_ = std::make_unique<Gpu>();
  gpu_->output = GlTexture2D(GL_R32F, in.width, in.height);
  gpu_->framebuffer.attach_color(0, gpu_->output);
  gpu_->framebuffer.check_complete("HBAO output");

  const AoSettings ao = settings_for(in.scene);
  ShaderDefines defines = binding_defines();
  defines.set("HBAO_DIRECTIONS", std::to_string(hbao_.directions));
  defines.set("HBAO_STEPS", std::to_string(hbao_.steps));
  defines.set("HBAO_ATTENUATED", ao.attenuated ? 1 : 0);
  gpu_->program = build_program({{GL_VERTEX_SHADER, "passes/fullscreen.vert", {}},
                                 {GL_FRAGMENT_SHADER, "passes/hbao.frag", {}}},
                                defines);
  const CameraFrame camera = camera_frame(in.scene.camera, in.width, in.height);
  const GlProgram& p = gpu_->program;
  p.set("camera_eye", camera.eye.x, camera.eye.y, camera.eye.z);
  p.set("camera_forward", camera.forward.x, camera.forward.y, camera.forward.z);
  p.set("focal_pixels", 0.5f * float(in.height) / camera.tan_half_fov_y);
  p.set("hbao_radius", ao.d_max);
  p.set("hbao_angle_bias", hbao_.angle_bias);
  const std::array<glm::vec2, 16> table = jitter_table();
  glProgramUniform2fv(p.id(), p.uniform("hbao_jitter"), GLsizei(table.size()), &table[0].x);
  check_gl("HBAO uniforms");
}

void Hbao::render(GpuTimer* timer) {
  gbuffer_->render(*gpu_scene_, *scene_, timer);
  ScopedSubpass timed(timer, "hbao");
  glBindFramebuffer(GL_FRAMEBUFFER, gpu_->framebuffer.id());
  glViewport(0, 0, width_, height_);
  glDisable(GL_DEPTH_TEST);
  glBindTextureUnit(0, gbuffer_->positions().id());
  glBindTextureUnit(1, gbuffer_->normals().id());
  gpu_->program.use();
  glBindVertexArray(gpu_->empty_vao.id());
  glDrawArrays(GL_TRIANGLES, 0, 3);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

std::vector<PassImage> Hbao::images() const {
  return {{"ao", image_from_gl_rows(gpu_->output.read_floats(1), width_, height_, 1)}};
}

std::vector<std::pair<std::string, RecordValue>> Hbao::results() const {
  const AoRange range = ao_range(images().front().image, gbuffer_->read_positions());
  return {{"ao_max", range.max}, {"ao_fraction_above_1", range.fraction_above_1}};
}

ReferenceResult Hbao::reference(const Scene& scene, int width, int height,
                                const ReferenceSettings& settings) const {
  // The same converged AO as the LDM pass's (the same key: one cache entry serves both).
  return ao_reference_for_run(scene, settings_for(scene), width, height, settings);
}

}  // namespace ldm
