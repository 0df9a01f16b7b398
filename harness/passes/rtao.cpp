#include "harness/passes/rtao.h"


#include "harness/reference/ao_reference.h"
#include "harness/reference/embree_scene.h"
#include "harness/reference/pixel_renderer.h"
#include "harness/reference/reference_settings.h"

namespace ldm {
namespace {

constexpr uint64_t kDefaultSeed = 0x5254414fu;  // "RTAO"

}  // namespace

Rtao::Rtao(StructureParams& params) {
  spp_ = uint32_t(params.get_uint("spp", 1, 1, 65536));
  threads_ = int(params.get_uint("threads", 0, 0, 1024));
  seed_ = params.get_uint("seed", kDefaultSeed, 0, uint64_t(1) << 53);  // exact in JSON
  if (params.has("d_max")) overrides_.d_max = float(params.get_double("d_max", 0.0, 1e-30, 1e30));
  const std::string visibility =
      params.get_choice("visibility", "scene", {"scene", "attenuated", "unattenuated"});
  if (visibility != "scene") overrides_.attenuated = visibility == "attenuated";
}

Rtao::~Rtao() = default;

AoSettings Rtao::settings_for(const Scene& scene) const {
  return apply_ao_overrides(scene.ao, overrides_);
}

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
  const AoSettings ao = settings_for(scene);
  return {{"visibility", std::string(ao.attenuated ? "attenuated" : "unattenuated")},
          {"d_max", double(ao.d_max)},
          {"falloff_exponent", double(ao.falloff_exponent)},
          {"rtao_spp", int64_t(spp_)},
          {"rtao_seed", int64_t(seed_)}};
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

std::vector<std::pair<std::string, RecordValue>> Rtao::results() const {
  return {{"rtao_threads", int64_t(threads_used())}, {"rtao_bvh_ms", bvh_ms_}};
}

ReferenceResult Rtao::reference(const Scene& scene, int width, int height,
                                const ReferenceSettings& settings) const {
  return ao_reference_for_run(scene, settings_for(scene), width, height, settings);
}

}  // namespace ldm
