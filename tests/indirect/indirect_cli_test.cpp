// `ldmbench run --pass indirect`: complete records scored against both lighting references,
// the pass's parameters as comma-list axes, every column described, all three images written.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include <nlohmann/json.hpp>

#include "harness/settings/record_schema.h"
#include "support/run_records.h"

namespace ldm {
namespace {

namespace fs = std::filesystem;

TEST(IndirectCli, RecordsAreCompleteAndScoredTwice) {
  const test::RunRecords run = test::run_records(
      "indirect", "--scene cornell --structure psppsll,dfbuffer --pass indirect -N 4 -R 32 --param indirect:s=2,6 "
                  "--param indirect:r_light=16 --width 24 --height 24 --frames 1 --time-target 0 --warmup 1 --reference-spp 8");
  ASSERT_EQ(run.records.size(), 4u) << "2 structures x 2 values of s";
  std::set<std::string> ids;
  for (const auto& r : run.records) {
    EXPECT_EQ(r["status"], "ok") << r["status_detail"];
    ids.insert(r["config_id"].get<std::string>());
    for (const char* key :
         {"gbuffer_ms_median", "light_gbuffer_ms_median", "photon_tracing_ms_median",
          "splatting_ms_median", "direct_ms_median", "composite_ms_median", "build_ms_median",
          "photons_primary", "photons_emitted", "photons_stored", "photons_overflow",
          "m_lists_allocated", "m_photons_allocated", "m_photons_used", "mse", "mssim",
          "ref_noise_mse", "multi_mse", "multi_mssim", "multi_ref_noise_mse", "splat_scale"})
      EXPECT_TRUE(r.contains(key) && r[key].is_number()) << key;
    EXPECT_EQ(r["payload"], "depth") << "the structures store depth alone";
    EXPECT_EQ(r["scene_attributes"], "position+normal+material");
    EXPECT_NE(r["ref_cache_key"], r["multi_ref_cache_key"]);
    for (const char* image : {"image_exr", "image_direct_exr", "image_sum_png", "reference_exr",
                              "multi_reference_exr"})
      EXPECT_TRUE(fs::exists(run.out / r[image].get<std::string>())) << image;
    for (const auto& [key, value] : r.items()) EXPECT_NE(find_column(key), nullptr) << key;
  }
  EXPECT_EQ(ids.size(), 4u);
  EXPECT_EQ(run.records[0]["splat_scale"], 2.0);
}

TEST(IndirectCli, BadParametersAreRejectedBeforeAnyWork) {
  for (const char* bad : {"--param indirect:s=0", "--param indirect:r_light=1,,2",
                          "--param indirect:shape=round", "--d-max 2"})
    test::refused_run("--scene cornell --pass indirect " + std::string(bad));
}

}  // namespace
}  // namespace ldm
