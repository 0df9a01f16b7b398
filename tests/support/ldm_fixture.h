#pragma once
// An LdmSetup for tests: scenes by name, normals uploaded, and a one-call build().
#include <memory>
#include <string>

#include "harness/measuring/ldm_setup.h"
#include "harness/scene/scene_loader.h"
#include "ldm_impls/common/ldm_inspector.h"
#include "support/test_support.h"

namespace ldm::test {

inline AttributeSet with_normals(bool normals) {
  gl_context();  // the setup uploads to the GPU: make sure a context exists
  AttributeSet a;
  a.normals = normals;
  return a;
}

struct LdmFixture : LdmSetup {
  LdmFixture(Scene s, uint32_t n, uint32_t r, bool normals = true)
      : LdmSetup(std::move(s), with_normals(normals), n, r) {}
  LdmFixture(const std::string& scene_name, uint32_t n, uint32_t r)
      : LdmFixture(load_scene(scene_name), n, r) {}
  // Structures sized by `sizing` (the census is taken all the same, for checks).
  LdmFixture(const std::string& scene_name, uint32_t n, uint32_t r, SizingSettings sizing)
      : LdmSetup(load_scene(scene_name), with_normals(true), n, r, FragmentPayload{}, sizing) {}

  // A prepared and built structure.
  std::unique_ptr<LdmStructure> build(const std::string& name,
                                      std::map<std::string, std::string> params = {}) const {
    auto s = prepare(name, std::move(params));
    s->build(*inputs, nullptr);
    return s;
  }
};

}  // namespace ldm::test
