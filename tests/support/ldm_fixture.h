#pragma once
// An LdmSetup for tests: scenes by name, normals uploaded, and a one-call build().
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "harness/measuring/ldm_setup.h"
#include "harness/scene/scene_loader.h"
#include "harness/util/error.h"
#include "ldm_impls/common/ldm_inspector.h"
#include "ldm_impls/ldm_structure.h"
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

// `structure` built into a fixed pool of half the census's fragments: the overflow is detected
// and counted exactly, and what is stored is whole sorted lists.
inline void expect_fixed_pool_overflow_counted(const LdmFixture& f, const std::string& structure) {
  const uint64_t capacity = f.census.total_fragments / 2;
  const auto s = f.build(structure, {{"capacity", std::to_string(capacity)}});
  const BuildStats stats = s->stats();
  EXPECT_TRUE(stats.overflow) << structure;
  EXPECT_EQ(stats.fragments_rasterized, f.census.total_fragments) << structure;
  EXPECT_EQ(stats.fragments_stored, capacity) << structure;
  EXPECT_EQ(stats.fragments_lost, f.census.total_fragments - capacity) << structure;
  const LdmIntegrity integrity = LdmInspector(*s, *f.inputs).check();
  EXPECT_EQ(integrity.fragments, capacity) << structure;
  EXPECT_EQ(integrity.unsorted_pixels, 0u) << structure;
}

using ParamValues = std::map<std::string, std::string>;

// make_structure(structure, ...) refuses each of `refused` with a UserError and accepts each
// of `accepted`.
inline void expect_params_checked(const std::string& structure, const std::vector<ParamValues>& refused,
                                  const std::vector<ParamValues>& accepted = {}) {
  gl_context();
  for (const ParamValues& p : refused)
    EXPECT_THROW(make_structure(structure, StructureParams(p)), UserError) << structure << " " << p.begin()->first;
  for (const ParamValues& p : accepted)
    EXPECT_NO_THROW(make_structure(structure, StructureParams(p))) << structure << " " << p.begin()->first;
}

}  // namespace ldm::test
