// The indirect pass's references (Embree, harness/reference/lighting_reference.h; no GL):
// the single-bounce indirect light the method approximates (LDDE paths) is the main one, the
// multi-bounce indirect light (what a full renderer shows) the second, under prefix multi_.
#include "harness/passes/indirect_lighting.h"
#include "harness/reference/lighting_reference.h"

namespace ldm {

ReferenceResult IndirectLighting::reference(const Scene& scene, int width, int height,
                                            const ReferenceSettings& settings) const {
  return lighting_reference_for_run(scene, LightingComponent::single_bounce, width, height,
                                    settings);
}

std::vector<ScoredReference> IndirectLighting::references(const Scene& scene, int width,
                                                          int height,
                                                          const ReferenceSettings& settings) const {
  std::vector<ScoredReference> out;
  for (const auto& [prefix, component] :
       {std::pair<const char*, LightingComponent>{"", LightingComponent::single_bounce},
        {"multi_", LightingComponent::multi_bounce}}) {
    ScoredReference scored;
    scored.column_prefix = prefix;
    scored.reference = lighting_reference_for_run(scene, component, width, height, settings);
    scored.ssim_exposure = lighting_ssim_exposure(scored.reference.image);
    out.push_back(std::move(scored));
  }
  return out;
}

}  // namespace ldm
