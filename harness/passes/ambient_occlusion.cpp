#include "harness/passes/ambient_occlusion.h"

#include <cstdio>

#include "harness/metrics/ao_range.h"
#include "harness/passes/ao_parameters.h"
#include "harness/reference/ao_reference.h"
#include "harness/reference/reference_settings.h"
#include "harness/util/error.h"

namespace ldm {

AmbientOcclusion::AmbientOcclusion(StructureParams& params) : AoPassBase(params) {
  // An absent key keeps the scene's value (d_max and visibility: AoPassBase).
  if (params.has("normal_offset_pixels"))
    overrides_.normal_offset_pixels = float(params.get_double("normal_offset_pixels"));
  overrides_.trace = parse_ao_trace(params.get_choice("trace"));
  overrides_.estimator = parse_ao_estimator(params.get_choice("ao_estimator"));
}

std::vector<AxisSpec> AmbientOcclusion::parameters() {
  return {ao_pass_parameter(AoAxis::DMax), ao_pass_parameter(AoAxis::Visibility),
          ao_pass_parameter(AoAxis::NormalOffset), ao_pass_parameter(AoAxis::Trace),
          ao_pass_parameter(AoAxis::Estimator)};
}

std::vector<WorkCounter> AmbientOcclusion::work_counters() {
  return with_gbuffer_counters({
      {"ao", "covered_pixels", WorkShape::Total, "pixels", "ao: image pixels that see a surface and trace every view"},
      {"ao", "entries_read", WorkShape::Distribution, "fragments",
       "ao: fragments the LDM trace read per view traced (one per covered pixel and view; 0 outside the view)"},
      {"ao", "trace_steps", WorkShape::Distribution, "iterations",
       "ao: loop iterations per view traced: the walk's and the structure's own query loops' (trace_steps_max's count)"},
  });
}

std::vector<ColumnSpec> AmbientOcclusion::columns() {
  return ao_pass_columns(true, {}, true);
}

PassRequirements AmbientOcclusion::requirements() const {
  // AO reads positions (every pass) and normals (the G-buffer); the structures store depth
  // alone.
  PassRequirements r;
  r.scene_attributes.normals = true;
  return r;
}

std::vector<TimedSubpass> AmbientOcclusion::subpasses() const {
  return {{"gbuffer", "G-buffer: world positions and camera-facing normals from the camera"},
          {"ao", "AO trace through the structure's query API (thesis §4.4)"}};
}

std::vector<std::pair<std::string, RecordValue>> AmbientOcclusion::describe(
    const Scene& scene) const {
  return ao_setting_values(settings_for(scene), true);
}

void AmbientOcclusion::prepare(const PassInputs& in) {
  if (!in.ldm || !in.structure) throw UserError("the ao pass needs an LDM structure");
  scene_ = &in.scene;
  gpu_scene_ = &in.gpu_scene;
  gbuffer_ = std::make_unique<GBufferPass>(in.width, in.height);
  ao_ = std::make_unique<AoPass>(*in.structure, *in.ldm, in.width, in.height,
                                 settings_for(in.scene));
}

void AmbientOcclusion::render(GpuTimer* timer) {
  gbuffer_->render(*gpu_scene_, *scene_, timer);
  ao_->render(*gbuffer_, timer);
}

std::vector<PassImage> AmbientOcclusion::images() const { return {{"ao", ao_->read_image()}}; }

std::vector<std::string> AmbientOcclusion::warnings() const {
  const AoSettings ao = settings_for(*scene_);
  if (ao.trace == AoTrace::Interval && ao.normal_offset_pixels <= kIntervalMinNormalOffset) {
    char text[200];
    std::snprintf(text, sizeof text,
                  "trace interval with a normal offset of %g px (needs more than %.2f px): "
                  "x's own surface is taken for an occluder",
                  double(ao.normal_offset_pixels), kIntervalMinNormalOffset);
    return {text};
  }
  return {};
}

Image AmbientOcclusion::coverage() const { return coverage_mask(gbuffer_->read_positions()); }

std::vector<std::pair<std::string, RecordValue>> AmbientOcclusion::results() const {
  // Eq. 13 may exceed 1 (a quadrature of the cosine): say how far, over covered pixels.
  std::vector<std::pair<std::string, RecordValue>> out =
      ao_range_results(ao_->read_image(), gbuffer_->read_positions());
  for (auto& field : trace_step_fields(ao_->trace_steps())) out.push_back(std::move(field));
  return out;
}

std::vector<std::string> AmbientOcclusion::problems() const {
  const std::string cut = trace_step_problem(ao_->trace_steps());
  return cut.empty() ? std::vector<std::string>{} : std::vector<std::string>{cut};
}

ReferenceResult AmbientOcclusion::reference(const Scene& scene, int width, int height,
                                            const ReferenceSettings& settings) const {
  return ao_reference_for_run(scene, settings_for(scene), width, height, settings);
}

}  // namespace ldm
