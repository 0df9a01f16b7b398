#include "harness/passes/indirect_lighting.h"

#include <cmath>

#include "harness/metrics/ao_range.h"
#include "harness/util/error.h"

namespace ldm {

IndirectLighting::IndirectLighting(StructureParams& params) {
  IndirectSettings& s = settings_;
  s.splat_scale = float(params.get_double("s", s.splat_scale, 1e-6, 1e6));
  if (params.has("a")) s.topological_bias = float(params.get_double("a", 0.0, 0.0, 1e6));
  s.footprint_threshold = float(params.get_double("t_foot", INFINITY, 1e-30, INFINITY));
  if (params.has("depth_threshold"))
    s.depth_threshold = float(params.get_double("depth_threshold", 0.0, 0.0, INFINITY));
  s.light_resolution = uint32_t(params.get_uint("r_light", s.light_resolution, 1, 4096));
  if (params.has("photon_capacity"))
    s.photon_capacity = params.get_uint("photon_capacity", 0, 0, uint64_t(1) << 32);
  if (params.has("photon_budget_mib"))
    s.photon_budget_mib = params.get_double("photon_budget_mib", 0.0, 0.0, 1e6);
  // The run's AO axes: the trace variant and normal offset apply to the photons' trace; the
  // AO estimator, d_max and visibility do not apply to light.
  s.trace = parse_ao_trace(
      params.get_choice("trace", ao_trace_name(kDefaultAoTrace), ao_trace_names()));
  if (params.has("normal_offset_pixels"))
    normal_offset_pixels_ = float(params.get_double("normal_offset_pixels", 0.0, 0.0, 1000.0));
  params.get_choice("ao_estimator", "eq13", {"eq13"});  // AO only: only its default is accepted
  if (params.has("d_max") || params.has("visibility"))
    throw UserError("--pass indirect: --d-max and --visibility are AO settings and do not "
                    "apply to the indirect pass");
}

IndirectSettings IndirectLighting::settings_for(const Scene& scene) const {
  IndirectSettings s = settings_;
  s.normal_offset_pixels = normal_offset_pixels_.value_or(scene.ao.normal_offset_pixels);
  return s;
}

PassRequirements IndirectLighting::requirements() const {
  // Normals (both G-buffers) and per-triangle materials (their albedo); the structures store
  // depth alone, as for AO: the photons' hits take normal and albedo from the G-buffers.
  PassRequirements r;
  r.scene_attributes.normals = true;
  r.scene_attributes.materials = true;
  return r;
}

std::vector<TimedSubpass> IndirectLighting::subpasses() const {
  return {{"gbuffer", "camera G-buffer: positions, camera-facing normals, albedo"},
          {"light_gbuffer", "the spot light's G-buffer, R_light^2 (positions, normals, albedo): "
                            "primary photons and the shadow map"},
          {"photon_census", "sizing policy census: a counting photon trace (census only)", false},
          {"photon_reallocate", "sizing policy census: growing the photon buffer", false},
          {"photon_tracing", "photon differentials traced through the LDM (thesis §5.4.1)"},
          {"photon_readback", "sizing policy previous_frame: the photon counter read back", false},
          {"photon_rebuild", "previous_frame: the photon buffer grown and the trace run again", false},
          {"splatting", "photon splats: point -> footprint quad -> Silverman kernel, additive "
                        "(§5.4.2)"},
          {"direct", "shadow-mapped direct light from the spot"},
          {"composite", "direct + indirect"}};
}

std::vector<std::pair<std::string, RecordValue>> IndirectLighting::describe(
    const Scene& scene) const {
  const IndirectSettings s = settings_for(scene);
  return {{"r_light", int64_t(s.light_resolution)},
          {"splat_scale", double(s.splat_scale)},
          {"topological_bias", double(s.a())},
          {"footprint_threshold", double(s.footprint_threshold)},
          {"trace", ao_trace_name(s.trace)},
          {"normal_offset_pixels", double(s.normal_offset_pixels)}};
}

void IndirectLighting::prepare(const PassInputs& in) {
  if (!in.ldm || !in.structure) throw UserError("the indirect pass needs an LDM structure");
  scene_ = &in.scene;
  gpu_scene_ = &in.gpu_scene;
  structure_ = in.structure;
  gbuffer_ = std::make_unique<GBufferPass>(in.width, in.height, true);
  lighting_ = std::make_unique<PhotonLighting>(*in.structure, *in.ldm, in.scene, in.width,
                                               in.height, settings_for(in.scene));
}

void IndirectLighting::render(GpuTimer* timer) {
  gbuffer_->render(*gpu_scene_, *scene_, timer);
  lighting_->render(*gbuffer_, timer);
}

std::vector<PassImage> IndirectLighting::images() const {
  return {{"indirect", lighting_->read_indirect()},
          {"direct", lighting_->read_direct()},
          {"sum", lighting_->read_sum()}};
}

std::vector<std::pair<std::string, RecordValue>> IndirectLighting::results() const {
  const PhotonCounts c = lighting_->counts();
  std::vector<std::pair<std::string, RecordValue>> out = {
      {"photons_primary", int64_t(c.primary)},
      {"photons_primary_degenerate", int64_t(c.primary_degenerate)},
      {"photons_emitted", int64_t(c.emitted)},
      {"photons_escaped", int64_t(c.escaped)},
      {"photons_culled_depth", int64_t(c.culled_depth)},
      {"photons_culled_footprint", int64_t(c.culled_footprint)},
      {"photons_degenerate", int64_t(c.degenerate)},
      {"photons_stored", int64_t(c.stored)},
      {"photons_overflow", int64_t(c.overflow)},
      {"depth_threshold", double(lighting_->depth_threshold())},
      {"covered_pixel_fraction", covered_pixel_fraction(gbuffer_->read_positions())},
      {"photon_rebuilds", int64_t(lighting_->rebuilds())},
      {"photon_reallocations", int64_t(lighting_->reallocations())}};
  for (const auto& [key, value] : lighting_->sizing()) out.emplace_back("sizing_" + key, value);
  for (auto& field : trace_step_fields(lighting_->trace_steps())) out.push_back(std::move(field));
  // The thesis's M_lists (the structure's storage) and M_photons (the photon buffer).
  uint64_t lists_allocated = 0, lists_used = 0;
  for (const auto& b : structure_->memory()) {
    lists_allocated += b.allocated;
    lists_used += b.used;
  }
  out.emplace_back("m_lists_allocated", int64_t(lists_allocated));
  out.emplace_back("m_lists_used", int64_t(lists_used));
  for (const auto& b : lighting_->memory())
    if (b.name == "photons") {
      out.emplace_back("m_photons_allocated", int64_t(b.allocated));
      out.emplace_back("m_photons_used", int64_t(b.used));
    }
  // Where the light's flux went (W, mean of the RGB channels): into primary photons, into
  // the secondaries emitted, and into those stored.
  double primary = 0, emitted = 0, stored = 0;
  const auto tally = lighting_->read_tally();
  for (size_t i = 0; i + 1 < tally.size(); i += 2) {
    primary += (tally[i].x + tally[i].y + tally[i].z) / 3.0;
    emitted += (tally[i + 1].x + tally[i + 1].y + tally[i + 1].z) / 3.0;
  }
  for (const auto& p : lighting_->read_photons()) stored += (p.flux.x + p.flux.y + p.flux.z) / 3.0;
  out.emplace_back("flux_primary", primary);
  out.emplace_back("flux_emitted", emitted);
  out.emplace_back("flux_stored", stored);
  return out;
}

std::vector<std::string> IndirectLighting::problems() const {
  const std::string cut = trace_step_problem(lighting_->trace_steps());
  return cut.empty() ? std::vector<std::string>{} : std::vector<std::string>{cut};
}

std::string IndirectLighting::loss() const {
  const PhotonCounts c = lighting_->counts();
  if (c.overflow == 0) return {};
  return "photon buffer overflow: " + std::to_string(c.overflow) + " of " +
         std::to_string(c.appended) + " photons not stored (capacity " +
         std::to_string(c.capacity) + ")";
}

std::vector<BufferMemory> IndirectLighting::memory() const { return lighting_->memory(); }

}  // namespace ldm
