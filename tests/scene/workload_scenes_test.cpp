// The thesis's two workload extremes as generators (issue 22): the hairball (even, high depth
// complexity) and the Sponza-like atrium (uneven; thin layers), and the depth-complexity
// profile the records carry.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "harness/scene/generators.h"
#include "harness/scene/scene_loader.h"
#include "harness/util/error.h"
#include "harness/util/hash.h"
#include "ldm_impls/common/fragment_census.h"
#include "support/test_support.h"

namespace ldm {
namespace {

namespace fs = std::filesystem;

Scene hairball(const nlohmann::json& params) { return generate_scene("hairball", params, "test"); }

TEST(Hairball, StrandsStayInsideTheBallAndTheSeedFixesThem) {
  const Scene a = hairball({{"strands", 50}, {"radius", 2.0}});
  const Scene b = hairball({{"strands", 50}, {"radius", 2.0}});
  const Scene c = hairball({{"strands", 50}, {"radius", 2.0}, {"seed", 7}});
  EXPECT_EQ(a.content_hash(), b.content_hash());
  EXPECT_NE(a.content_hash(), c.content_hash());
  // 14 segments x 3 sides x 2 triangles, and a triangle capping each end, per strand.
  EXPECT_EQ(a.mesh.triangle_count(), 50u * (14 * 3 * 2 + 2));
  const float tube = 0.006f * 2.0f;
  for (const glm::vec3& p : a.mesh.positions) ASSERT_LE(glm::length(p), 2.0f + tube * 1.01f);
  EXPECT_GT(a.bounding_sphere().radius, 1.5f);  // the strands fill the ball, not a corner of it
  EXPECT_NO_THROW(a.validate());
}

TEST(Hairball, DensityAndSizeAreParameters) {
  const Scene sparse = hairball({{"strands", 20}});
  const Scene dense = hairball({{"strands", 80}, {"segments", 7}, {"sides", 4}});
  EXPECT_EQ(sparse.mesh.triangle_count(), 20u * (14 * 3 * 2 + 2));
  EXPECT_EQ(dense.mesh.triangle_count(), 80u * (7 * 4 * 2 + 2 * 2));
  const Scene big = hairball({{"strands", 20}, {"radius", 100.0}});
  EXPECT_NEAR(big.bounding_sphere().radius / sparse.bounding_sphere().radius, 100.0f, 5.0f);
  EXPECT_NEAR(big.ao.d_max / sparse.ao.d_max, 100.0f, 1e-3f);  // d_max follows the size
  EXPECT_THROW(hairball({{"strands", 0}}), UserError);
  EXPECT_THROW(hairball({{"sides", 2}}), UserError);
  EXPECT_THROW(hairball({{"thickness", 1}}), UserError);  // unknown key
}

TEST(SponzaLike, TheDefaultAtriumIsTheOneTheCommittedSweepMeasured) {
  // The new features are off by default: the atrium's content (and so its cached references
  // and every earlier record) is unchanged. Its hash as the committed default report has it.
  std::ifstream tidy(fs::path(LDM_TEST_SOURCE_DIR) / ".." / "docs" / "reports" / "default" / "tidy.csv");
  ASSERT_TRUE(tidy) << "docs/reports/default/tidy.csv";
  std::string header, line;
  std::getline(tidy, header);
  std::vector<std::string> columns;
  for (std::stringstream h(header); std::getline(h, line, ',');) columns.push_back(line);
  const auto scene_col = std::find(columns.begin(), columns.end(), "scene_name") - columns.begin();
  const auto hash_col = std::find(columns.begin(), columns.end(), "scene_hash") - columns.begin();
  std::string committed;
  while (committed.empty() && std::getline(tidy, line)) {
    // The leading columns hold no quoted commas up to these two (device, with its comma,
    // comes before: split quotes-aware).
    const std::vector<std::string> cells = test::split_csv_line(line);
    if (cells.size() > size_t(hash_col) && cells[size_t(scene_col)] == "atrium" && !cells[size_t(hash_col)].empty())
      committed = cells[size_t(hash_col)];
  }
  ASSERT_FALSE(committed.empty());
  EXPECT_EQ(hex64(generate_scene("atrium", nullptr, "test").content_hash()), committed);
}

TEST(SponzaLike, StoreysDrapesPlantsAndChainsAddWhatTheThesisScenesHave) {
  const Scene atrium = generate_scene("atrium", nullptr, "test");
  auto with = [](nlohmann::json params) { return generate_scene("atrium", params, "test"); };
  const Scene third = with({{"storeys", 3}});
  EXPECT_GT(third.bounds().hi.y, atrium.bounds().hi.y + 1.0f);  // a storey higher
  const Scene drapes = with({{"drapes", 4}});
  const Scene plants = with({{"plants", 4}, {"leaves", 100}});
  const Scene chains = with({{"chains", 4}});
  EXPECT_GT(drapes.mesh.triangle_count(), atrium.mesh.triangle_count());
  // A pot (10 sides: 40 triangles) and 100 leaves of 2 triangles each, per plant.
  EXPECT_EQ(plants.mesh.triangle_count(), atrium.mesh.triangle_count() + 4 * (40 + 200));
  EXPECT_EQ(chains.mesh.triangle_count(), atrium.mesh.triangle_count() + 4 * 24);
  // The scene file that turns them all on loads.
  const Scene sponza = load_scene((fs::path(LDM_TEST_SOURCE_DIR) / ".." / "scenes" / "sponza_like.json").string());
  EXPECT_EQ(sponza.name, "sponza-like");
  EXPECT_GT(sponza.mesh.triangle_count(), 2 * atrium.mesh.triangle_count());
  EXPECT_THROW(with({{"storeys", 4}}), UserError);
}

TEST(DepthProfile, QuantilesHistogramAndShareAboveK) {
  FragmentCensus census;
  // 10 empty pixels, then lengths 1 (x5), 2 (x3), 5 (x1), 9 (x1): 10 non-empty pixels.
  census.counts = std::vector<uint32_t>(10, 0);
  for (uint32_t n : {1u, 1u, 1u, 1u, 1u, 2u, 2u, 2u, 5u, 9u}) census.counts.push_back(n);
  census.total_pixels = census.counts.size();
  census.max_depth_complexity = 9;
  const DepthProfile p = depth_profile(census);
  EXPECT_EQ(p.nonempty_pixels, 10u);
  EXPECT_EQ(p.p50, 1u);   // the 5th of 10
  EXPECT_EQ(p.p90, 5u);   // the 9th
  EXPECT_EQ(p.p99, 9u);   // the 10th
  EXPECT_EQ(p.max, 9u);
  EXPECT_EQ(p.quantile(0.6), 2u);
  EXPECT_DOUBLE_EQ(p.share_above(1), 0.5);
  EXPECT_DOUBLE_EQ(p.share_above(4), 0.2);
  EXPECT_DOUBLE_EQ(p.share_above(9), 0.0);
  EXPECT_EQ(p.histogram_text(), "1:5;2-3:3;4-7:1;8-9:1");
  // An empty census has an empty profile.
  FragmentCensus none;
  none.counts = {0, 0};
  none.total_pixels = 2;
  const DepthProfile e = depth_profile(none);
  EXPECT_EQ(e.p99, 0u);
  EXPECT_EQ(e.histogram_text(), "");
  EXPECT_DOUBLE_EQ(e.share_above(0), 0.0);
}

}  // namespace
}  // namespace ldm
