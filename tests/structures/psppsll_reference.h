#pragma once
// What the HA-buffer and fixed-array tests compare against: the same scene and views built
// with PSPPSLL (the reference structure, itself checked against Embree in tests/psppsll),
// read back through the same query API, and AO rendered through any structure.
#include <gtest/gtest.h>

#include <memory>
#include <vector>

#include "harness/passes/ao_pass.h"
#include "harness/passes/gbuffer_pass.h"
#include "support/ldm_fixture.h"

namespace ldm::test {

inline StructureParams params(std::map<std::string, std::string> values) {
  return StructureParams(std::move(values));
}

using ViewLists = std::vector<std::vector<float>>;  // one view: depths per pixel, nearest first

inline std::vector<ViewLists> read_all_views(const LdmStructure& structure, const LdmFixture& f) {
  const LdmInspector inspector(structure, *f.inputs);
  std::vector<ViewLists> views;
  for (uint32_t v = 0; v < f.views.size(); ++v) views.push_back(inspector.read_back(v));
  return views;
}

struct PsppsllReference {
  std::unique_ptr<LdmStructure> structure;
  std::vector<ViewLists> lists;
  LdmIntegrity integrity;
};

// Builds PSPPSLL and checks that it holds every fragment of the census, so that differences
// found later are the tested structure's.
inline PsppsllReference build_psppsll_reference(const LdmFixture& f) {
  PsppsllReference r;
  r.structure = f.build("psppsll");
  EXPECT_EQ(r.structure->stats().fragments_lost, 0u) << "the reference itself lost fragments";
  r.lists = read_all_views(*r.structure, f);
  r.integrity = LdmInspector(*r.structure, *f.inputs).check();
  EXPECT_EQ(r.integrity.fragments, f.census.total_fragments);
  return r;
}

// AO of the fixture's scene from its camera, size x size pixels, through `structure`.
inline Image render_ao(const LdmStructure& structure, const LdmFixture& f, int size) {
  GBufferPass gbuffer(size, size);
  AoPass ao(structure, *f.inputs, size, size, f.scene.ao);
  gbuffer.render(*f.gpu_scene, f.scene, nullptr);
  ao.render(gbuffer, nullptr);
  return ao.read_image();
}

// Fragments in `reference` missing from `lists` (pixel by pixel; negative if `lists` has more).
inline int64_t missing_fragments(const std::vector<ViewLists>& reference,
                                 const std::vector<ViewLists>& lists) {
  int64_t missing = 0;
  for (size_t v = 0; v < reference.size(); ++v)
    for (size_t p = 0; p < reference[v].size(); ++p)
      missing += int64_t(reference[v][p].size()) - int64_t(lists[v][p].size());
  return missing;
}

inline double stats_counter(const BuildStats& stats, const std::string& name) {
  for (const auto& [key, value] : stats.counters)
    if (key == name) return value;
  ADD_FAILURE() << "BuildStats has no counter '" << name << "'";
  return -1;
}

inline std::string sizing_value(const LdmStructure& structure, const std::string& name) {
  for (const auto& [key, value] : structure.sizing())
    if (key == name) return value;
  ADD_FAILURE() << structure.name() << ".sizing() has no '" << name << "'";
  return {};
}

}  // namespace ldm::test
