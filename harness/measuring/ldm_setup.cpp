#include "harness/measuring/ldm_setup.h"

namespace ldm {

namespace {
// The one place where the census reaches a sizing plan: the oracle policy, by definition.
SizingPlan make_sizing_plan(const SizingSettings& settings, const FragmentCensus& census) {
  if (settings.policy != SizingPolicy::Oracle)
    return plan_without_census(settings, census.total_pixels);
  SizingPlan plan;
  plan.policy = SizingPolicy::Oracle;
  plan.initial = census_needs(census);
  plan.initial_source = "census (untimed, before the run)";
  return plan;
}
}  // namespace

LdmSetup::LdmSetup(Scene s, AttributeSet attributes, uint32_t view_count, uint32_t resolution,
                   FragmentPayload payload, SizingSettings sizing_settings)
    : scene(centred_on_bounding_sphere(s)) {
  gpu_scene = std::make_unique<GpuScene>(scene, attributes);
  views = make_view_set(scene.bounding_sphere(), view_count, resolution);
  gpu_views = std::make_unique<GpuViewSet>(views);
  raster = std::make_unique<RasterFragmentSource>(*gpu_scene, *gpu_views);
  census = take_fragment_census(*raster, views);
  sizing = make_sizing_plan(sizing_settings, census);
  inputs = std::make_unique<BuildInputs>(
      BuildInputs{*gpu_scene, *gpu_views, sizing, payload, *raster});
}

std::unique_ptr<LdmStructure> LdmSetup::prepare(const std::string& structure,
                                                std::map<std::string, std::string> params) const {
  auto s = make_structure(structure, StructureParams(std::move(params), "--param " + structure));
  s->prepare(*inputs);
  return s;
}

}  // namespace ldm
