#pragma once
// What every measurement of a structure builds on: the scene on the GPU (only the attributes
// the passes read), its LDM views, their fragment census (untimed: verification, and the
// sizes of the oracle policy only) and the sizing plan the structures see. Owned together
// because the build inputs refer to them. Used by `ldmbench run`, the Google Benchmark
// binary and the tests.
#include <map>
#include <memory>
#include <string>

#include "ldm_impls/common/ldm_rasterizer.h"
#include "ldm_impls/common/fragment_census.h"
#include "ldm_impls/ldm_structure.h"

namespace ldm {

struct LdmSetup {
  // The scene in its centred frame (centred_on_bounding_sphere): the geometry, the LDM views
  // and every pass (camera, light, G-buffer positions) use it, so that depths and positions
  // are computed in coordinates of the scene's extent, whatever its distance from the world
  // origin. Add scene.frame_origin to a position read back to get world coordinates.
  Scene scene;
  std::unique_ptr<GpuScene> gpu_scene;
  ViewSet views;
  std::unique_ptr<GpuViewSet> gpu_views;
  FragmentCensus census;  // verification; never reachable through `inputs`
  SizingPlan sizing;
  std::unique_ptr<RasterFragmentSource> raster;  // the scene rasterised into the views
  std::unique_ptr<BuildInputs> inputs;

  LdmSetup(Scene scene, AttributeSet attributes, uint32_t view_count, uint32_t resolution,
           FragmentPayload payload = {}, SizingSettings sizing = {});
  LdmSetup(const LdmSetup&) = delete;
  LdmSetup& operator=(const LdmSetup&) = delete;

  // A structure with its storage sized for this setup (prepare() done, nothing built yet).
  std::unique_ptr<LdmStructure> prepare(const std::string& structure,
                                        std::map<std::string, std::string> params = {}) const;
};

}  // namespace ldm
