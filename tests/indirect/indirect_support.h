#pragma once
// The indirect pass run directly (no records): a setup with normals and materials, a
// structure built once, the pass prepared and rendered once.
#include <map>
#include <memory>
#include <string>

#include "harness/measuring/ldm_setup.h"
#include "harness/passes/indirect_lighting.h"
#include "harness/scene/scene_loader.h"
#include "support/test_support.h"

namespace ldm::test {

inline AttributeSet lighting_attributes() {
  gl_context();
  AttributeSet a;
  a.normals = true;
  a.materials = true;
  return a;
}

struct IndirectRun {
  std::unique_ptr<LdmSetup> setup;
  std::unique_ptr<LdmStructure> structure;
  std::unique_ptr<IndirectLighting> pass;

  IndirectRun(Scene scene, const std::string& structure_name, uint32_t n, uint32_t r, int size,
              std::map<std::string, std::string> params = {},
              std::map<std::string, std::string> structure_params = {}) {
    setup = std::make_unique<LdmSetup>(std::move(scene), lighting_attributes(), n, r);
    structure = setup->prepare(structure_name, std::move(structure_params));
    structure->build(*setup->inputs, nullptr);
    StructureParams p(std::move(params), "indirect test");
    p.declare(IndirectLighting::parameters());
    pass = std::make_unique<IndirectLighting>(p);
    p.check("pass indirect");
    pass->prepare({setup->scene, *setup->gpu_scene, setup->inputs.get(), structure.get(), size,
                   size});
    pass->render(nullptr);
  }
  const PhotonLighting& lighting() const { return pass->lighting(); }
  Image indirect() const { return lighting().read_indirect(); }
};

}  // namespace ldm::test
