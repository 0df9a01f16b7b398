#include "harness/passes/hbao.h"

#include <cmath>

#include "harness/gl/bindings.h"
#include "harness/gl/gl_objects.h"
#include "harness/metrics/ao_range.h"
#include "harness/reference/ao_reference.h"
#include "harness/reference/reference_settings.h"
#include "harness/passes/ao_parameters.h"
#include "harness/scene/camera.h"
#include "harness/util/error.h"

namespace ldm {

Hbao::Hbao(StructureParams& params) : AoPassBase(params) {
  hbao_.directions = uint32_t(params.get_uint("directions"));
  hbao_.steps = uint32_t(params.get_uint("steps"));
  hbao_.angle_bias = float(params.get_double("angle_bias"));
  hbao_.jitter = params.get_choice("jitter") == "on";
  hbao_.blur_radius = uint32_t(params.get_uint("blur"));
}

std::vector<AxisSpec> Hbao::parameters() {
  return {numeric_parameter("directions", AxisKind::UInt, 1, 256, "8", "directions", "N_HBAO screen-space directions sampled per pixel",
                            "hbao_directions"),
          numeric_parameter("steps", AxisKind::UInt, 1, 512, "8", "steps", "S_HBAO ray-marching steps per direction, out to d_max",
                            "hbao_steps"),
          numeric_parameter("angle_bias", AxisKind::Real, 0.0, 1.5, "0.1", "radians",
                            "horizon angle bias (ignores tangent-plane occluders)", "hbao_angle_bias"),
          choice_parameter("jitter", {"off", "on"}, "off", "per-pixel rotation of the directions", "hbao_jitter"),
          numeric_parameter("blur", AxisKind::UInt, 0, 16, "0", "pixels", "cross-bilateral blur radius after the AO, timed as blur (0: none)",
                            "hbao_blur"),
          ao_pass_parameter(AoAxis::DMax), ao_pass_parameter(AoAxis::Visibility)};
}

// The AO settings' columns and the AO range; each of its parameters declares its own column
// (pass_columns()).
std::vector<ColumnSpec> Hbao::columns() {
  return ao_pass_columns(false, {}, true);
}

// The horizon search's counters, declared once for HBAO and GTAO (hbao_kernel.h); what is
// HBAO's own is what it searches and how its samples and steps are described.
std::vector<WorkCounter> Hbao::work_counters() {
  return horizon_search_work_counters(
      "hbao", "blur",
      {.searched = "directions",
       .searched_what = "directions marched (of N_HBAO per covered pixel, those whose tangent plus the "
                        "angle bias stays below the zenith)",
       .samples_what = "G-buffer samples the march read (directions x S_HBAO where no march leaves the image)",
       .steps_what = "march steps (samples read) per covered pixel, over its directions"});
}

Hbao::~Hbao() = default;

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
  return ao_setting_values(settings_for(scene), false);
}

void Hbao::prepare(const PassInputs& in) {
  auto kernel = std::make_unique<HbaoKernel>(hbao_, settings_for(in.scene), in.width, in.height);
  kernel->set_camera(ScreenSpaceAo<HbaoKernel>::smoothing_camera(in));
  frame_.prepare(in, std::move(kernel), hbao_.blur_radius);
}

void Hbao::render(GpuTimer* timer) { frame_.render(timer); }
std::vector<PassImage> Hbao::images() const { return frame_.images(); }
std::vector<BufferMemory> Hbao::memory() const { return frame_.memory(); }
Image Hbao::coverage() const { return frame_.coverage(); }
std::vector<std::pair<std::string, RecordValue>> Hbao::results() const { return frame_.results(); }

ReferenceResult Hbao::reference(const Scene& scene, int width, int height,
                                const ReferenceSettings& settings) const {
  // The same converged AO as the LDM pass's (the same key: one cache entry serves both).
  return ao_reference_for_run(scene, settings_for(scene), width, height, settings);
}

}  // namespace ldm
