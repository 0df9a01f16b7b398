// The indirect pass's references (kept apart: the Embree side, no GL).
#include "harness/passes/indirect_lighting.h"
#include "harness/util/error.h"

namespace ldm {

ReferenceResult IndirectLighting::reference(const Scene&, int, int,
                                            const ReferenceSettings&) const {
  throw UserError("TEMPORARY: lighting references not merged yet");
}

std::vector<ScoredReference> IndirectLighting::references(const Scene& scene, int width,
                                                          int height,
                                                          const ReferenceSettings& settings) const {
  return {{"", reference(scene, width, height, settings), 1.0}};
}

}  // namespace ldm
