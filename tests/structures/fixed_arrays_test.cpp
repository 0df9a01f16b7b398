// PPFLA and PSPPFLA (thesis §3.2.6, §3.2.7) against PSPPSLL on the same scene and views:
// with the default k (under the fixtures' oracle policy, the census's maximum depth complexity) both store every fragment and
// read back bit-identical lists; with a smaller k the lost fragments are counted exactly,
// and PSPPFLA keeps each pixel's k nearest.
#include <gtest/gtest.h>

#include <algorithm>

#include "harness/util/error.h"
#include "structures/structure_test_support.h"

namespace ldm {
namespace {

using test::LdmFixture;
using test::ViewLists;

// The default k is the census's maximum depth complexity: nothing is lost. (That the lists
// then equal PSPPSLL's is the conformance suite's, conformance_test.cpp.)
void expect_default_k_is_the_census_maximum(const std::string& structure_name) {
  const LdmFixture f("cornell", 8, 32);
  const auto structure = f.build(structure_name);
  EXPECT_EQ(test::sizing_value(*structure, "k"), std::to_string(f.census.max_depth_complexity));
  EXPECT_EQ(test::sizing_value(*structure, "k_source"), "oracle");
  EXPECT_EQ(structure->stats().fragments_lost, 0u);
}

TEST(Ppfla, DefaultKIsTheCensusMaximum) {
  expect_default_k_is_the_census_maximum("ppfla");
}
TEST(Psppfla, DefaultKIsTheCensusMaximum) {
  expect_default_k_is_the_census_maximum("psppfla");
}
// k below the maximum depth complexity: fragments_lost must be the census's count of
// fragments beyond k, each pixel must keep min(n, k) of its fragments, sorted.
struct LossyBuild {
  std::unique_ptr<LdmStructure> structure;
  std::vector<ViewLists> lists;
  uint32_t k = 0;
};

LossyBuild expect_exact_loss_count(const std::string& structure_name, const LdmFixture& f,
                                   const test::PsppsllReference& reference) {
  LossyBuild b;
  b.k = std::max(1u, f.census.max_depth_complexity / 2);
  EXPECT_GT(f.census.fragments_beyond(b.k), 0u) << "the scene is too shallow to test loss";
  b.structure = f.build(structure_name, {{"k", std::to_string(b.k)}});
  const BuildStats stats = b.structure->stats();
  EXPECT_EQ(stats.fragments_lost, f.census.fragments_beyond(b.k));
  EXPECT_TRUE(stats.overflow) << "a lossy build must say so";
  EXPECT_EQ(stats.fragments_stored + stats.fragments_lost, f.census.total_fragments);
  EXPECT_EQ(test::stats_counter(stats, "dropped_beyond_k"), double(stats.fragments_lost));
  const LdmIntegrity integrity = LdmInspector(*b.structure, *f.inputs).check();
  EXPECT_EQ(integrity.unsorted_pixels, 0u);
  EXPECT_EQ(integrity.fragments, stats.fragments_stored);
  b.lists = test::read_all_views(*b.structure, f);
  EXPECT_EQ(test::missing_fragments(reference.lists, b.lists),
            int64_t(f.census.fragments_beyond(b.k)));
  uint64_t wrong_lengths = 0;
  for (size_t v = 0; v < b.lists.size(); ++v)
    for (size_t p = 0; p < b.lists[v].size(); ++p)
      wrong_lengths += b.lists[v][p].size() != std::min<size_t>(reference.lists[v][p].size(), b.k);
  EXPECT_EQ(wrong_lengths, 0u);
  return b;
}

TEST(Psppfla, SmallKKeepsTheNearestFragmentsAndCountsTheRest) {
  const LdmFixture f("atrium", 12, 64);
  const auto reference = test::build_psppsll_reference(f);
  const LossyBuild b = expect_exact_loss_count("psppfla", f, reference);
  // Insertion by atomicMin keeps the k nearest: PSPPSLL's prefix, bit for bit.
  std::vector<ViewLists> prefixes = reference.lists;
  for (auto& view : prefixes)
    for (auto& list : view) list.resize(std::min<size_t>(list.size(), b.k));
  test::expect_bit_identical_lists(prefixes, b.lists, "psppfla k=" + std::to_string(b.k));
}

TEST(Ppfla, SmallKCountsTheLostFragmentsExactly) {
  const LdmFixture f("atrium", 12, 64);
  const auto reference = test::build_psppsll_reference(f);
  const LossyBuild b = expect_exact_loss_count("ppfla", f, reference);
  // PPFLA keeps whichever k arrived first: every kept depth must be one of the pixel's.
  uint64_t foreign = 0;
  for (size_t v = 0; v < b.lists.size(); ++v)
    for (size_t p = 0; p < b.lists[v].size(); ++p) {
      std::vector<float> all = reference.lists[v][p];
      for (float d : b.lists[v][p]) {
        const auto it = std::find(all.begin(), all.end(), d);
        if (it == all.end()) {
          ++foreign;
        } else {
          all.erase(it);
        }
      }
    }
  EXPECT_EQ(foreign, 0u);
}

// PSPPFLA's lossy result does not depend on arrival order either: it is the k nearest.
TEST(Psppfla, RepeatedLossyBuildsGiveIdenticalChecksums) {
  const LdmFixture f("atrium", 8, 32);
  ASSERT_GT(f.census.fragments_beyond(2), 0u);
  const auto lossy = f.build("psppfla", {{"k", "2"}});
  const LdmInspector inspector(*lossy, *f.inputs);
  const LdmIntegrity first = inspector.check();
  for (int i = 0; i < 2; ++i) {
    lossy->build(*f.inputs, nullptr);
    EXPECT_EQ(lossy->stats().fragments_lost, f.census.fragments_beyond(2));
    EXPECT_EQ(inspector.check(), first) << "rebuild " << i + 1;
  }
}

TEST(FixedArrays, MemoryIsPixelsTimesKWords) {
  const LdmFixture f("cornell", 8, 32);
  const uint64_t pixels = f.views.total_pixels();
  for (const std::string name : {"ppfla", "psppfla"}) {
    const auto structure = f.build(name, {{"k", "5"}});
    EXPECT_EQ(test::sizing_value(*structure, "k"), "5");
    EXPECT_EQ(test::sizing_value(*structure, "k_source"), "parameter");
    uint64_t entries = 0, total = 0;
    for (const BufferMemory& m : structure->memory()) {
      if (m.name == "entries") entries = m.allocated;
      total += m.allocated;
    }
    EXPECT_EQ(entries, pixels * 5 * sizeof(uint32_t)) << name;
    // PPFLA adds one count per pixel; both add a 4-byte drop counter.
    EXPECT_EQ(total, entries + (name == "ppfla" ? pixels * sizeof(uint32_t) : 0) + 4) << name;
  }
}

TEST(FixedArrays, KBeyondTheStorageBlockIsAUserError) {
  const LdmFixture f("cornell", 8, 32);
  GLint64 block = 0;
  glGetInteger64v(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &block);
  // The smallest k whose entries exceed the block (or 32-bit indices, whichever comes first).
  const uint64_t pixels = f.views.total_pixels();
  const uint64_t k = std::min<uint64_t>(uint64_t(block) / (pixels * 4) + 1, 1u << 20);
  for (const std::string name : {"ppfla", "psppfla"}) {
    auto structure = make_structure(name, test::params({{"k", std::to_string(k)}}));
    try {
      structure->prepare(*f.inputs);
      ADD_FAILURE() << name << " accepted k=" << k;
    } catch (const UserError& e) {
      EXPECT_NE(std::string(e.what()).find("k = " + std::to_string(k)), std::string::npos)
          << e.what();
    }
  }
}

}  // namespace
}  // namespace ldm
