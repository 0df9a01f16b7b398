#include "harness/passes/gtao.h"

#include "harness/metrics/ao_range.h"
#include "harness/passes/ao_parameters.h"
#include "harness/passes/hbao_kernel.h"
#include "harness/reference/ao_reference.h"
#include "harness/reference/reference_settings.h"
#include "harness/scene/camera.h"

namespace ldm {
namespace {

AxisSpec numeric(const char* key, AxisKind kind, double lo, double hi, const char* fallback,
                 const char* unit, const char* description) {
  return numeric_parameter(key, kind, lo, hi, fallback, unit, description, std::string("gtao_") + key);
}

AxisSpec choice(const char* key, std::vector<std::string> choices, const char* fallback,
                const char* description) {
  return choice_parameter(key, std::move(choices), fallback, description, std::string("gtao_") + key);
}

}  // namespace

Gtao::Gtao(StructureParams& params) : AoPassBase(params) {
  gtao_.slices = uint32_t(params.get_uint("slices"));
  gtao_.steps = uint32_t(params.get_uint("steps"));
  gtao_.radius_scale = float(params.get_double("radius"));
  gtao_.falloff = float(params.get_double("falloff"));
  gtao_.thickness = float(params.get_double("thickness"));
  gtao_.step_power = float(params.get_double("step_power"));
  gtao_.jitter = params.get_choice("jitter") == "on";
  gtao_.normalized = params.get_choice("estimator") == "normalized";
  gtao_.denoise_radius = uint32_t(params.get_uint("denoise"));
  gtao_.reference_weights = params.get_choice("attenuation") == "reference";
}

// The defaults are the measured optimum of docs/measured/gtao-rtao-gpu.md.
std::vector<AxisSpec> Gtao::parameters() {
  return {numeric("slices", AxisKind::UInt, 1, 64, "8", "slices", "slice planes through the view vector per pixel"),
          numeric("steps", AxisKind::UInt, 1, 128, "16", "steps", "horizon-search samples per side of a slice"),
          numeric("radius", AxisKind::Real, 0.05, 8, "1", "d_max", "search radius R as a multiple of d_max"),
          numeric("falloff", AxisKind::Real, 0, 1, "0", "", "fraction of R over which an occluder's weight fades to 0 (0: none)"),
          numeric("thickness", AxisKind::Real, 0, 1, "0", "", "thickness heuristic: how far a lower sample pulls the horizon back (0: height field)"),
          numeric("step_power", AxisKind::Real, 0.5, 4, "1.5", "", "sample distances R * u^power (> 1: denser near the pixel)"),
          choice("jitter", {"off", "on"}, "on", "per-pixel slice rotation and step offset (4x4 Bayer pattern)"),
          choice("estimator", {"mean", "normalized"}, "normalized", "mean over the slices (the paper) or normalized by their open hemispheres"),
          choice("attenuation", {"reference", "binary"}, "reference", "occluder weight: the reference's 1 - V(r), or 1 within R (the engines' binary horizon, faded by falloff)"),
          numeric("denoise", AxisKind::UInt, 0, 16, "0", "pixels", "cross-bilateral denoise radius after the AO, timed as denoise (0: none)"),
          ao_pass_parameter(AoAxis::DMax), ao_pass_parameter(AoAxis::Visibility)};
}

// The AO settings' columns and the AO range; each of its parameters declares its own column
// (pass_columns()).
std::vector<ColumnSpec> Gtao::columns() {
  return ao_pass_columns(false, {}, true);
}

// The horizon search's counters, declared once for HBAO and GTAO (hbao_kernel.h); what is
// GTAO's own is what it searches and how its samples and steps are described.
std::vector<WorkCounter> Gtao::work_counters() {
  return horizon_search_work_counters(
      "gtao", "denoise",
      {.searched = "slices",
       .searched_what = "slices searched on both sides (of the slices per covered pixel, those on "
                        "screen, with a normal not normal to the slice and a radius of at least a pixel)",
       .samples_what = "G-buffer samples the horizon search read (slices x 2 sides x steps where no "
                       "search leaves the image)",
       .steps_what = "search steps (samples read) per covered pixel, over its slices' both sides"});
}

Gtao::~Gtao() = default;

PassRequirements Gtao::requirements() const {
  PassRequirements r;
  r.scene_attributes.normals = true;  // the G-buffer's shading normals: the hemisphere's axis
  r.needs_structure = false;
  return r;
}

std::vector<TimedSubpass> Gtao::subpasses() const {
  std::vector<TimedSubpass> subpasses = {
      {"gbuffer", "G-buffer: world positions and camera-facing normals from the camera"},
      {"gtao", "GTAO: slices x 2 sides x steps horizon samples per pixel, cosine-weighted closed-form integral"}};
  if (gtao_.denoise_radius > 0)
    subpasses.push_back({"denoise", "GTAO: separable cross-bilateral blur of the AO (--param gtao:denoise=)"});
  return subpasses;
}

std::vector<std::pair<std::string, RecordValue>> Gtao::describe(const Scene& scene) const {
  return ao_setting_values(settings_for(scene), false);
}

void Gtao::prepare(const PassInputs& in) {
  auto kernel = std::make_unique<GtaoKernel>(gtao_, settings_for(in.scene), in.width, in.height);
  const CameraFrame frame = camera_frame(in.scene.camera, in.width, in.height);
  const float focal_pixels = 0.5f * float(in.height) / frame.tan_half_fov_y;
  kernel->set_camera({frame.eye, frame.forward, frame.right, frame.up, focal_pixels});
  frame_.prepare(in, std::move(kernel), gtao_.denoise_radius);
}

void Gtao::render(GpuTimer* timer) { frame_.render(timer); }
std::vector<PassImage> Gtao::images() const { return frame_.images(); }
std::vector<BufferMemory> Gtao::memory() const { return frame_.memory(); }
Image Gtao::coverage() const { return frame_.coverage(); }
std::vector<std::pair<std::string, RecordValue>> Gtao::results() const { return frame_.results(); }

ReferenceResult Gtao::reference(const Scene& scene, int width, int height,
                                const ReferenceSettings& settings) const {
  // The AO reference every AO-like pass shares (one cache entry).
  return ao_reference_for_run(scene, settings_for(scene), width, height, settings);
}

}  // namespace ldm
