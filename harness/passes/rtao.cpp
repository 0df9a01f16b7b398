#include "harness/passes/rtao.h"

#include "harness/passes/ao_parameters.h"


#include "harness/reference/ao_reference.h"
#include "harness/reference/embree_scene.h"
#include "harness/reference/pixel_renderer.h"
#include "harness/reference/reference_settings.h"

namespace ldm {
namespace {

constexpr uint64_t kRtaoDefaultSeed = 0x5254414fu;  // "RTAO"

}  // namespace

Rtao::Rtao(StructureParams& params) : AoPassBase(params) {
  spp_ = uint32_t(params.get_uint("spp"));
  threads_ = int(params.get_uint("threads"));
  seed_ = params.get_uint("seed");
}

// Each parameter in one designated initializer (the fields in AxisSpec's order), as
// harness/scene/ao_axes.cpp declares the AO axes; the fields left out keep their defaults.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
std::vector<AxisSpec> Rtao::parameters() {
  return {{.key = "spp", .kind = AxisKind::UInt, .min = 1, .max = 65536, .default_value = "1",
           .unit = "samples per pixel", .description = "rays per pixel (cosine-weighted, Embree)",
           .column = "rtao_spp"},
          // Not identity: how fast, not what; the image is the same with any count.
          {.key = "threads", .kind = AxisKind::UInt, .min = 0, .max = 1024, .default_value = "0",
           .identity = false, .unit = "threads", .description = "CPU threads tracing (0: every core)",
           .column = "rtao_threads"},
          {.key = "seed", .kind = AxisKind::UInt, .min = 0, .max = double(uint64_t(1) << 53),  // exact in JSON
           .default_value = std::to_string(kRtaoDefaultSeed),
           .description = "seed of the sample stream (independent of the reference's halves)",
           .column = "rtao_seed"},
          ao_pass_parameter(AoAxis::DMax), ao_pass_parameter(AoAxis::Visibility)};
}
#pragma GCC diagnostic pop

// Its own columns after the AO settings': a data table, alike in form only to the other
// passes'.
std::vector<ColumnSpec> Rtao::columns() {
  return ao_pass_columns(false, {
      {"pass", "rtao_bvh_ms", "ms", "RTAO: wall time of the Embree BVH build, once before the frames (static scene; not in frame)",
       ColumnKind::Number, VariesBetweenRuns::Yes},
  }, false);
}

Rtao::~Rtao() = default;

int Rtao::threads_used() const { return render_worker_count(threads_, width_, height_); }

PassRequirements Rtao::requirements() const {
  PassRequirements r;  // positions only: nothing is drawn, the scene is traced on the CPU
  r.needs_structure = false;
  r.runs_on_cpu = true;
  return r;
}

std::vector<TimedSubpass> Rtao::subpasses() const {
  return {{"rtao", "RTAO: Embree on the CPU, primary ray and spp AO rays per pixel (CPU wall time)"}};
}

std::vector<std::pair<std::string, RecordValue>> Rtao::describe(const Scene& scene) const {
  return ao_setting_values(settings_for(scene), false);
}

void Rtao::prepare(const PassInputs& in) {
  in.scene.validate();
  ao_ = settings_for(in.scene);
  width_ = in.width;
  height_ = in.height;
  const auto start = std::chrono::steady_clock::now();
  centred_ = std::make_unique<Scene>(centred_on_bounding_sphere(in.scene));
  embree_ = std::make_unique<EmbreeScene>(*centred_);
  bvh_ms_ = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
                .count();
}

void Rtao::render(GpuTimer* timer) {
  ScopedSubpass timed(timer, "rtao");
  image_ = render_ao_half(*embree_, ao_, width_, height_, spp_, seed_, kRtaoStreamPass,
                          threads_, false);
}

std::vector<PassImage> Rtao::images() const { return {{"ao", image_}}; }

// The threads parameter's column holds the threads it traced with (0, every core, resolved
// here), in place of the configuration's value (pass_parameter_values()).
std::vector<std::pair<std::string, RecordValue>> Rtao::results() const {
  return {{find_axis(parameters(), "threads")->column, int64_t(threads_used())}, {"rtao_bvh_ms", bvh_ms_}};
}

ReferenceResult Rtao::reference(const Scene& scene, int width, int height,
                                const ReferenceSettings& settings) const {
  return ao_reference_for_run(scene, settings_for(scene), width, height, settings);
}

}  // namespace ldm
