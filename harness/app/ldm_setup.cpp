#include "harness/app/ldm_setup.h"

namespace ldm {

LdmSetup::LdmSetup(Scene s, AttributeSet attributes, uint32_t view_count, uint32_t resolution,
                   FragmentPayload payload)
    : scene(std::move(s)) {
  gpu_scene = std::make_unique<GpuScene>(scene, attributes);
  views = make_view_set(scene.bounding_sphere(), view_count, resolution);
  gpu_views = std::make_unique<GpuViewSet>(views);
  raster = std::make_unique<RasterFragmentSource>(*gpu_scene, *gpu_views);
  census = take_fragment_census(*raster, views);
  inputs = std::make_unique<BuildInputs>(
      BuildInputs{*gpu_scene, *gpu_views, census, payload, *raster});
}

std::unique_ptr<LdmStructure> LdmSetup::prepare(const std::string& structure,
                                                std::map<std::string, std::string> params) const {
  auto s = make_structure(structure, StructureParams(std::move(params), "--param " + structure));
  s->prepare(*inputs);
  return s;
}

}  // namespace ldm
