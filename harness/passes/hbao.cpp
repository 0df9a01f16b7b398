#include "harness/passes/hbao.h"

#include <cmath>

#include "harness/gl/bindings.h"
#include "harness/gl/gl_objects.h"
#include "harness/metrics/ao_range.h"
#include "harness/reference/ao_reference.h"
#include "harness/reference/reference_settings.h"
#include "harness/scene/camera.h"
#include "harness/util/error.h"

namespace ldm {

Hbao::Hbao(StructureParams& params) {
  hbao_.directions = uint32_t(params.get_uint("directions", hbao_.directions, 1, 256));
  hbao_.steps = uint32_t(params.get_uint("steps", hbao_.steps, 1, 512));
  hbao_.angle_bias = float(params.get_double("angle_bias", hbao_.angle_bias, 0.0, 1.5));
  hbao_.jitter = params.get_choice("jitter", "off", {"off", "on"}) == "on";
  hbao_.blur_radius = uint32_t(params.get_uint("blur", 0, 0, 16));
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
  std::vector<TimedSubpass> subpasses = {
      {"gbuffer", "G-buffer: world positions and camera-facing normals from the camera"},
      {"hbao", "HBAO: horizon search in the G-buffer, N_HBAO x S_HBAO samples per pixel (then blur, with --param hbao:blur=R)"}};
  if (hbao_.blur_radius > 0)
    subpasses.push_back({"blur", "HBAO: separable cross-bilateral blur of the AO (--param hbao:blur=)"});
  return subpasses;
}

std::vector<std::pair<std::string, RecordValue>> Hbao::describe(const Scene& scene) const {
  const AoSettings ao = settings_for(scene);
  return {{"visibility", std::string(ao.attenuated ? "attenuated" : "unattenuated")},
          {"d_max", double(ao.d_max)},
          {"falloff_exponent", double(ao.falloff_exponent)},
          {"hbao_directions", int64_t(hbao_.directions)},
          {"hbao_steps", int64_t(hbao_.steps)},
          {"hbao_angle_bias", double(hbao_.angle_bias)},
          {"hbao_jitter", std::string(hbao_.jitter ? "on" : "off")},
          {"hbao_blur", int64_t(hbao_.blur_radius)}};
}

void Hbao::prepare(const PassInputs& in) {
  scene_ = &in.scene;
  gpu_scene_ = &in.gpu_scene;
  width_ = in.width;
  height_ = in.height;
  gbuffer_ = std::make_unique<GBufferPass>(in.width, in.height);
  kernel_ = std::make_unique<HbaoKernel>(hbao_, settings_for(in.scene), in.width, in.height);
  const CameraFrame frame = camera_frame(in.scene.camera, in.width, in.height);
  const HbaoCamera camera{frame.eye, frame.forward, 0.5f * float(in.height) / frame.tan_half_fov_y};
  kernel_->set_camera(camera);
  if (hbao_.blur_radius > 0) {
    blur_ = std::make_unique<HbaoBlur>(hbao_.blur_radius, kernel_->target());
    blur_->set_camera(camera);
  }
}

void Hbao::render(GpuTimer* timer) {
  gbuffer_->render(*gpu_scene_, *scene_, timer);
  {
    ScopedSubpass timed(timer, "hbao");
    kernel_->run(gbuffer_->positions(), gbuffer_->normals());
  }
  if (blur_) {
    ScopedSubpass timed(timer, "blur");
    blur_->run(gbuffer_->positions(), gbuffer_->normals());
  }
}

std::vector<PassImage> Hbao::images() const {
  return {{"ao", image_from_gl_rows(kernel_->target().read_floats(1), width_, height_, 1)}};
}

std::vector<BufferMemory> Hbao::memory() const {
  // Render targets, every texel written each frame (allocated = used). The G-buffer is
  // counted too: the LDM AO draws the same one, but its records count only its structure.
  std::vector<BufferMemory> targets = gbuffer_->memory();
  const uint64_t ao_bytes = kernel_->target().bytes();
  targets.push_back({"hbao_ao", ao_bytes, ao_bytes});
  if (blur_) targets.push_back({"hbao_blur_scratch", blur_->scratch().bytes(), blur_->scratch().bytes()});
  return targets;
}

std::vector<std::pair<std::string, RecordValue>> Hbao::results() const {
  const AoRange range = ao_range(images().front().image, gbuffer_->read_positions());
  return {{"ao_max", range.max},
          {"ao_fraction_above_1", range.fraction_above_1},
          {"covered_pixel_fraction", covered_pixel_fraction(gbuffer_->read_positions())}};
}

ReferenceResult Hbao::reference(const Scene& scene, int width, int height,
                                const ReferenceSettings& settings) const {
  // The same converged AO as the LDM pass's (the same key: one cache entry serves both).
  return ao_reference_for_run(scene, settings_for(scene), width, height, settings);
}

}  // namespace ldm
