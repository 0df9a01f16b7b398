// The reference cache's metadata is covered by its integrity check (issue 19, item 6):
// pixel corruption was detected and re-rendered, but an edited noise_mse in an entry's
// sidecar was used as it stood (mse_over_noise 4.7e9 instead of 156.7).
#include <gtest/gtest.h>

#include "harness/reference/ao_reference.h"
#include "harness/scene/generators.h"
#include "reliability_support.h"

namespace ldm::reliability {
namespace {

AoReferenceRequest small_request() {
  AoReferenceRequest r;
  r.width = r.height = 16;
  r.spp.spp_per_half = 8;
  r.threads = 2;
  r.progress = false;
  return r;
}

TEST(ReliabilityCache, EditedMetadataIsAMissNotAResult) {
  const std::string dir = test::make_temp_dir("ldm-cache");
  const Scene scene = generate_scene("parallel-planes", {{"h", 1.0}}, "test");
  const ReferenceResult first = cached_ao_reference(scene, small_request(), dir);
  ASSERT_FALSE(first.from_cache);
  ASSERT_TRUE(cached_ao_reference(scene, small_request(), dir).from_cache);
  const fs::path sidecar = fs::path(dir) / (first.cache_key + ".json");
  const nlohmann::json original = nlohmann::json::parse(test::read_text(sidecar.string()));
  ASSERT_TRUE(original.contains("checksum"));
  for (const char* key : {"noise_mse", "spp_total", "noise_target_met", "render_seconds"}) {
    nlohmann::json edited = original;
    if (std::string(key) == "noise_mse") edited[key] = original[key].get<double>() * 1e-7;
    else if (std::string(key) == "noise_target_met") edited[key] = !original[key].get<bool>();
    else edited[key] = original[key].get<double>() + 1;
    write_file(sidecar, edited.dump(2));
    const ReferenceResult again = cached_ao_reference(scene, small_request(), dir);
    EXPECT_FALSE(again.from_cache) << key << ": an edited entry was used";
    EXPECT_DOUBLE_EQ(again.noise_mse, first.noise_mse) << key;
    EXPECT_EQ(again.spp_total, first.spp_total) << key;
    // Rendered again and stored whole: the next request is a hit with the true metadata.
    const ReferenceResult hit = cached_ao_reference(scene, small_request(), dir);
    EXPECT_TRUE(hit.from_cache) << key;
    EXPECT_DOUBLE_EQ(hit.noise_mse, first.noise_mse) << key;
  }
  // An entry without a checksum (an older build's) is rendered again too.
  nlohmann::json old = original;
  old.erase("checksum");
  write_file(sidecar, old.dump(2));
  EXPECT_FALSE(cached_ao_reference(scene, small_request(), dir).from_cache);
}

}  // namespace
}  // namespace ldm::reliability
