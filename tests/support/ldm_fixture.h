#pragma once
// Everything needed to build an LDM structure on a scene in a test: the GPU scene, the views,
// the census and the build inputs, kept alive together.
#include <memory>
#include <string>

#include "harness/scene/scene_loader.h"
#include "ldm_impls/common/ldm_inspector.h"
#include "ldm_impls/ldm_structure.h"
#include "support/test_support.h"

namespace ldm::test {

struct LdmFixture {
  Scene scene;
  std::unique_ptr<GpuScene> gpu_scene;
  ViewSet views;
  std::unique_ptr<GpuViewSet> gpu_views;
  FragmentCensus census;
  std::unique_ptr<BuildInputs> inputs;

  LdmFixture(Scene s, uint32_t n, uint32_t r, bool normals = true) : scene(std::move(s)) {
    gl_context();
    AttributeSet attributes;
    attributes.normals = normals;
    gpu_scene = std::make_unique<GpuScene>(scene, attributes);
    views = make_view_set(scene.bounding_sphere(), n, r);
    gpu_views = std::make_unique<GpuViewSet>(views);
    census = take_fragment_census(*gpu_scene, *gpu_views);
    inputs = std::make_unique<BuildInputs>(BuildInputs{*gpu_scene, *gpu_views, census, {}});
  }
  LdmFixture(const std::string& scene_name, uint32_t n, uint32_t r)
      : LdmFixture(load_scene(scene_name), n, r) {}

  // A prepared and built structure.
  std::unique_ptr<LdmStructure> build(const std::string& name,
                                      std::map<std::string, std::string> params = {}) const {
    auto s = make_structure(name, StructureParams(std::move(params)));
    s->prepare(*inputs);
    s->build(*inputs, nullptr);
    return s;
  }
};

}  // namespace ldm::test
