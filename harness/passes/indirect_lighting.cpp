#include "harness/passes/indirect_lighting.h"

#include <cmath>
#include <cstdlib>
#include <limits>

#include "harness/metrics/ao_range.h"
#include "harness/passes/ao_parameters.h"
#include "harness/util/error.h"

namespace ldm {

IndirectLighting::IndirectLighting(StructureParams& params) {
  IndirectSettings& s = settings_;
  s.splat_scale = float(params.get_double("s"));
  if (params.has("a")) s.topological_bias = float(params.get_double("a"));
  if (params.has("t_foot")) s.footprint_threshold = float(params.get_double("t_foot"));
  if (params.has("depth_threshold")) s.depth_threshold = float(params.get_double("depth_threshold"));
  s.light_resolution = uint32_t(params.get_uint("r_light"));
  if (params.has("photon_capacity")) s.photon_capacity = params.get_uint("photon_capacity");
  if (params.has("photon_budget_mib")) s.photon_budget_mib = params.get_double("photon_budget_mib");
  s.emission = parse_photon_emission(params.get_choice("emission"));
  // The run's AO axes: the trace variant and normal offset apply to the photons' trace; the
  // AO estimator, d_max and visibility do not apply to light.
  s.trace = parse_ao_trace(params.get_choice("trace"));
  if (params.has("normal_offset_pixels"))
    normal_offset_pixels_ = float(params.get_double("normal_offset_pixels"));
  if (params.get_choice("ao_estimator") != ao_estimator_name(AoEstimatorChoice::Eq13))
    throw UserError("--pass indirect: --ao-estimator is an AO setting; the indirect pass takes "
                    "only its default, eq13");
  if (params.has("d_max") || params.has("visibility"))
    throw UserError("--pass indirect: --d-max and --visibility are AO settings and do not "
                    "apply to the indirect pass");
}

std::vector<AxisSpec> IndirectLighting::parameters() {
  auto real = [](const char* key, double lo, double hi, const char* fallback, const char* note,
                 const char* unit, const char* column, const char* description) {
    AxisSpec p = numeric_parameter(key, AxisKind::Real, lo, hi, fallback, unit, description, column);
    p.default_note = note;
    return p;
  };
  const double largest = 3.4028234663852886e38;  // FLT_MAX: any finite float
  AxisSpec r_light = numeric_parameter("r_light", AxisKind::UInt, 1, 4096, "64", "pixels",
                                       "the light's G-buffer is R_light x R_light: one primary photon per texel",
                                       "r_light");
  r_light.label = "R_light";
  AxisSpec capacity = numeric_parameter(
      "photon_capacity", AxisKind::UInt, 0, double(uint64_t(1) << 32), "", "photons",
      "fixes the photon buffer, overriding the sizing policy (overflow counted, lossy)");
  capacity.default_note = "sized by the sizing policy";
  const AxisSpec emission = choice_parameter(
      "emission", photon_emission_names(), photon_emission_name(PhotonEmission::Thesis),
      "how a primary photon's reflected flux is split among its secondaries: thesis (|cos| 2/N each, "
      "a quadrature, as AO's Eq. 13) or normalized (|cos| / their sum: exactly rho Phi1)",
      "emission");
  AxisSpec budget = real("photon_budget_mib", 0, 1e6, "", "the structure's budget", "MiB", "",
                         "budget policy: the photon buffer's own budget");
  budget.real_is_double = true;
  return {real("s", 1e-6, 1e6, "4", "", "", "splat_scale", "splat footprint scale s (1: one light texel's beam)"),
          real("a", 0, 1e6, "", "a = s (the thesis's choice)", "", "topological_bias",
               "topological bias a of the splat kernel: its cut off the photon's tangent plane (default: a = s)"),
          real("t_foot", 1e-30, largest, "", "off (no footprint test)", "scene units", "footprint_threshold",
               "T_foot: photons whose footprint s |D x| (max norm) exceeds it are culled (inf: off)"),
          real("depth_threshold", 0, largest, "", "3 LDM pixels", "scene units", "",
               "a photon's hit must lie within this distance of the camera G-buffer's depth to splat"),
          emission, r_light, capacity, budget,
          ao_pass_parameter(AoAxis::Trace), ao_pass_parameter(AoAxis::NormalOffset),
          ao_pass_parameter(AoAxis::Estimator), ao_pass_parameter(AoAxis::DMax),
          ao_pass_parameter(AoAxis::Visibility)};
}

// A data table of the pass's own counters, alike in form only to the other passes' and
// structures' (see ldm_impls/common/structure_counters.h).
std::vector<WorkCounter> IndirectLighting::work_counters() {
  std::vector<WorkCounter> counters = gbuffer_work_counters("gbuffer");
  for (WorkCounter c : gbuffer_work_counters("light_gbuffer")) counters.push_back(std::move(c));
  // The trace (photon_trace.comp) runs as photon_tracing every frame, and under the sizing
  // policies also as photon_census (census: counting only, capacity 0, nothing stored) and
  // photon_rebuild (previous_frame, after an overflow).
  for (const std::string subpass : {"photon_tracing", "photon_census", "photon_rebuild"}) {
    const std::string what = subpass + ": ";
    const std::vector<WorkCounter> trace = {
        {subpass, "invocations", WorkShape::Total, "invocations",
         what + "compute invocations over the light's texels (R_light^2)"},
        {subpass, "photons_primary", WorkShape::Total, "photons",
         what + "primary photons (light texels inside the cone that hit a surface; photons_primary)"},
        {subpass, "photons_traced", WorkShape::Total, "photons",
         what + "secondary photons traced through the LDM (photons_emitted)"},
        {subpass, "photons_appended", WorkShape::Total, "photons",
         what + "photons appended to the photon buffer, stored or not (photons_stored + photons_overflow)"},
        {subpass, "photons_stored", WorkShape::Total, "photons",
         what + "photons written into the photon buffer (how many is deterministic; which, under overflow, is not; "
                "0 in the census)"},
        {subpass, "trace_steps", WorkShape::Distribution, "iterations",
         what + "loop iterations per secondary photon traced: the walk's and the structure's own query loops'"},
        {subpass, "entries_read", WorkShape::Distribution, "fragments",
         what + "fragments the LDM trace read per secondary photon traced"},
    };
    counters.insert(counters.end(), trace.begin(), trace.end());
  }
  const std::vector<WorkCounter> own = {
      {"splatting", "vertices", WorkShape::Total, "invocations",
       "splatting: vertex shader invocations of the splat draw (one point per stored photon)"},
      {"splatting", "quads", WorkShape::Total, "quads",
       "splatting: footprint quads the geometry shader emitted (one per stored photon)"},
      {"splatting", "fragments", WorkShape::Total, "fragments",
       "splatting: fragments the splat quads shaded (helpers left out); grows with s^2 (thesis §6.2.2). "
       "Which photons are stored decides it, which arrival order decides only where the photon buffer "
       "overflowed: equal between runs otherwise",
       WorkOrder::ArrivalDependent},
      {"splatting", "fragments_in_kernel", WorkShape::Total, "fragments",
       "splatting: of those, fragments over a surface inside the kernel's support (blended into the image); "
       "equal between runs unless the photon buffer overflowed",
       WorkOrder::ArrivalDependent},
      {"direct", "fragments", WorkShape::Total, "fragments", "direct: fragments of the full-screen direct light (every image pixel)"},
      {"direct", "covered_pixels", WorkShape::Total, "pixels", "direct: image pixels that see a surface (lit or shadowed)"},
      {"composite", "fragments", WorkShape::Total, "fragments", "composite: fragments of the full-screen sum (every image pixel)"},
  };
  counters.insert(counters.end(), own.begin(), own.end());
  return counters;
}

std::vector<ColumnSpec> IndirectLighting::columns() {
  std::vector<ColumnSpec> columns = {
      {"pass", "normal_offset_pixels", "LDM pixels", "normal offset of thesis §4.4.2 (after --normal-offset)"},
      {"pass", "trace", "", "AO trace variant: listing5, interval or plane (after --trace)"},
      {"pass", "depth_threshold", "scene units", "indirect: tolerance of the photons' depth test against the camera G-buffer (default 3 LDM pixels; --param indirect:depth_threshold=)"},
      {"pass", "photons_primary", "photons", "indirect: light texels inside the cone that hit a surface (primary photons)"},
      {"pass", "photons_primary_degenerate", "photons", "indirect: primary photons whose transfer to the hit was degenerate (grazing), culled"},
      {"pass", "photons_emitted", "photons", "indirect: secondary photons emitted (of the 2N view directions, those in the hit's hemisphere)"},
      {"pass", "photons_escaped", "photons", "indirect: secondary photons whose LDM trace found no surface"},
      {"pass", "photons_culled_depth", "photons", "indirect: secondary photons whose hit the camera does not see (outside the image, behind the G-buffer's surface by more than depth_threshold, or its unlit side)"},
      {"pass", "photons_culled_outside", "photons", "indirect: of photons_culled_depth, those whose hit lies outside the image or over background"},
      {"pass", "photons_culled_hidden", "photons", "indirect: of photons_culled_depth, those whose hit lies behind the surface the camera sees there by more than depth_threshold"},
      {"pass", "photons_culled_backside", "photons", "indirect: of photons_culled_depth, those arriving on the side of the seen surface the camera does not see"},
      {"pass", "photons_culled_footprint", "photons", "indirect: secondary photons culled by T_foot"},
      {"pass", "photons_degenerate", "photons", "indirect: secondary photons with a degenerate differential (grazing transfer, opposite rotation, zero area, non-finite), culled"},
      {"pass", "photons_stored", "photons", "indirect: photons in the photon buffer (splatted)"},
      {"pass", "photons_unresolved", "photons", "indirect: stored photons whose splat footprint's half-width spans under 16 float steps at their position: floats cannot place or shape their kernels (the scene too large for the photons' detail), flagged in status_detail"},
      {"pass", "photon_footprint_steps_min", "float steps", "indirect: the narrowest stored photon's footprint half-width, in steps of the float grid at its position (16 or more: resolved; empty when none was stored)"},
      {"pass", "photons_overflow", "photons", "indirect: photons that did not fit the photon buffer (counted; makes the record lossy)"},
      {"pass", "photon_rebuilds", "frames", "indirect, previous_frame: traces repeated after the photon buffer overflowed (warm-up included)"},
      {"pass", "photon_reallocations", "frames", "indirect, census: photon buffer reallocations"},
      {"pass", "m_lists_allocated", "bytes", "indirect: the thesis's M_lists, the structure's storage (= bytes_allocated without the sizing policy's buffers)"},
      {"pass", "m_lists_used", "bytes", "indirect: M_lists used by the last build"},
      {"pass", "m_photons_allocated", "bytes", "indirect: the thesis's M_photons, the photon buffer (80 bytes a photon)"},
      {"pass", "m_photons_used", "bytes", "indirect: M_photons holding the last trace's photons"},
      {"pass", "flux_primary", "W", "indirect: flux of the primary photons (mean of RGB; the flux audit, docs/measured/indirect.md#flux-audit)"},
      {"pass", "flux_reflected", "W", "indirect: rho times the primary flux, over the primary photons that were split (what a perfect split emits)"},
      {"pass", "flux_emitted", "W", "indirect: flux emitted into secondary photons (flux_reflected exactly with emission normalized, up to the N-direction quadrature with thesis); = escaped + culled_* + degenerate + overflow + stored"},
      {"pass", "flux_escaped", "W", "indirect: flux of the secondary photons whose LDM trace found no surface"},
      {"pass", "flux_culled_outside", "W", "indirect: flux of the photons_culled_outside"},
      {"pass", "flux_culled_hidden", "W", "indirect: flux of the photons_culled_hidden"},
      {"pass", "flux_culled_backside", "W", "indirect: flux of the photons_culled_backside"},
      {"pass", "flux_culled_footprint", "W", "indirect: flux of the photons culled by T_foot"},
      {"pass", "flux_degenerate", "W", "indirect: flux of the secondary photons with a degenerate differential"},
      {"pass", "flux_overflow", "W", "indirect: flux of the photons that did not fit the photon buffer"},
      {"pass", "flux_stored", "W", "indirect: flux of the stored photons; = flux_splat_unseen + flux_splat_outside_quad - flux_splat_surface_area + flux_splat_clipped + flux_deposited"},
      {"pass", "flux_splat_unseen", "W", "indirect: of flux_stored, the splat kernels' mass over no surface the camera sees (off the image, background, hidden; on the photons' tangent planes), with the pixel quadrature's error"},
      {"pass", "flux_splat_outside_quad", "W", "indirect: of flux_stored, the kernels' mass over seen surface that the splat's quad does not cover (the surface curving away from the photon's plane)"},
      {"pass", "flux_splat_surface_area", "W", "indirect: flux gained where the surface under a splat has more area than its projection onto the photon's tangent plane"},
      {"pass", "flux_splat_clipped", "W", "indirect: of flux_stored, the kernels' mass cut by the topological bias a (points off the photon's tangent plane)"},
      {"pass", "flux_deposited", "W", "indirect: flux the splats deposit on the surfaces the image shows: the integral of pi L / rho over them (an untimed audit splat)"},
      {"pass", "visible_area", "scene units^2", "indirect: area of the surfaces the image shows (flux_deposited / visible_area is their mean indirect irradiance)"},
      {"pass", "image_order_tolerance", "", "indirect: the relative difference within which two runs' images, accuracy and flux_* columns agree (the splats blend, and the audits add, in the order the photons were appended: their float sums round differently); none where the photon buffer overflowed: which photons were stored then depends on arrival"},
  };
  for (ColumnSpec& column : columns)
    if (column.name == "flux_stored" || column.name == "flux_deposited" || column.name.rfind("flux_splat_", 0) == 0)
      column.summed_in_arrival_order = true;
  return columns;
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
  std::vector<std::pair<std::string, RecordValue>> out;
  // The value in effect of the two parameters with no declared default, where the
  // configuration gives none (a given value reaches the column as every parameter's does:
  // pass_parameter_values()): a = s, as s's column holds it (the canonical value, 0.1 rather
  // than the float's 0.10000000149011612), and T_foot off (inf, which no given value can be).
  const auto column = [](const char* key) { return find_axis(parameters(), key)->column; };
  if (!s.topological_bias) out.emplace_back(column("a"), std::strtod(shortest_text(s.a(), true).c_str(), nullptr));
  if (std::isinf(s.footprint_threshold)) out.emplace_back(column("t_foot"), double(s.footprint_threshold));
  // The AO axes it reads, in effect (the scene's normal offset where none is given).
  out.emplace_back("trace", ao_trace_name(s.trace));
  out.emplace_back("normal_offset_pixels", double(s.normal_offset_pixels));
  return out;
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

Image IndirectLighting::coverage() const { return coverage_mask(gbuffer_->read_positions()); }

std::vector<std::pair<std::string, RecordValue>> IndirectLighting::results() const {
  const PhotonCounts c = lighting_->counts();
  std::vector<std::pair<std::string, RecordValue>> out = {
      {"photons_primary", int64_t(c.primary)},
      {"photons_primary_degenerate", int64_t(c.primary_degenerate)},
      {"photons_emitted", int64_t(c.emitted)},
      {"photons_escaped", int64_t(c.escaped)},
      {"photons_culled_depth", int64_t(c.culled_depth)},
      {"photons_culled_outside", int64_t(c.culled_outside)},
      {"photons_culled_hidden", int64_t(c.culled_hidden())},
      {"photons_culled_backside", int64_t(c.culled_backside)},
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
  // The flux audit (W, mean of the RGB channels; docs/measured/indirect.md#flux-audit): where the light's
  // flux went in the trace (into primary photons, reflected, split into secondaries, and the
  // secondaries' fates), then the stored photons' flux followed into the image by an untimed
  // audit splat.
  const PhotonFluxTally t = lighting_->flux_tally();
  const std::vector<StoredPhoton> photons = lighting_->read_photons();
  double stored = 0;
  for (const auto& p : photons) stored += (p.flux.x + p.flux.y + p.flux.z) / 3.0;
  // Whether floats resolve the stored photons' footprints where they lie (issue 35).
  const PhotonResolution resolution = photon_resolution(photons, settings_.splat_scale);
  out.emplace_back("photons_unresolved", int64_t(resolution.unresolved));
  if (resolution.photons > 0) out.emplace_back("photon_footprint_steps_min", resolution.min_steps);
  out.emplace_back("flux_primary", t.primary);
  out.emplace_back("flux_reflected", t.reflected);
  out.emplace_back("flux_emitted", t.emitted);
  out.emplace_back("flux_escaped", t.escaped);
  out.emplace_back("flux_culled_outside", t.culled_outside);
  out.emplace_back("flux_culled_hidden", t.culled_hidden);
  out.emplace_back("flux_culled_backside", t.culled_backside);
  out.emplace_back("flux_culled_footprint", t.culled_footprint);
  out.emplace_back("flux_degenerate", t.degenerate);
  out.emplace_back("flux_overflow", t.overflow);
  out.emplace_back("flux_stored", stored);
  const SplatAudit a = lighting_->audit_splat(*gbuffer_);
  out.emplace_back("flux_splat_unseen", stored - a.tangent_all);
  out.emplace_back("flux_splat_outside_quad", a.tangent_all - a.tangent_in_quad);
  out.emplace_back("flux_splat_surface_area", a.uncut - a.tangent_in_quad);
  out.emplace_back("flux_splat_clipped", a.uncut - a.deposited);
  out.emplace_back("flux_deposited", a.deposited);
  out.emplace_back("visible_area", a.visible_area);
  if (std::isfinite(image_order_tolerance())) out.emplace_back("image_order_tolerance", image_order_tolerance());
  return out;
}

std::vector<std::string> IndirectLighting::problems() const {
  const std::string cut = trace_step_problem(lighting_->trace_steps());
  return cut.empty() ? std::vector<std::string>{} : std::vector<std::string>{cut};
}

std::vector<std::string> IndirectLighting::warnings() const {
  if (!lighting_) return {};  // not prepared: nothing stored
  const std::string detail =
      photon_resolution_detail(photon_resolution(lighting_->read_photons(), settings_.splat_scale));
  return detail.empty() ? std::vector<std::string>{} : std::vector<std::string>{detail};
}

void IndirectLighting::continue_sizing_from(const Pass& measured) {
  const auto* other = dynamic_cast<const IndirectLighting*>(&measured);
  if (other && other->lighting_ && lighting_) lighting_->continue_sizing_from(*other->lighting_);
}

double IndirectLighting::image_order_tolerance() const {
  return loss().empty() ? 1e-4 : std::numeric_limits<double>::infinity();
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
