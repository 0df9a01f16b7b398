// The disk cache of AO references: hits, misses on every key input, corrupt entries.
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "harness/reference/ao_reference.h"
#include "harness/scene/generators.h"
#include "support/test_support.h"

namespace ldm {
namespace {

class ReferenceCache : public ::testing::Test {
 protected:
  void SetUp() override { dir_ = test::make_temp_dir("ldm-reference-cache"); }
  void TearDown() override { std::filesystem::remove_all(dir_); }

  static Scene scene(double h = 1.0) {
    return generate_scene("parallel-planes", {{"h", h}}, "test");
  }
  static AoReferenceRequest request() {
    AoReferenceRequest r;
    r.width = r.height = 16;
    r.spp.spp_per_half = 8;
    r.threads = 2;
    r.progress = false;
    return r;
  }
  ReferenceResult cached(const Scene& s, const AoReferenceRequest& r) const {
    return cached_ao_reference(s, r, dir_);
  }
  std::string path_of(const ReferenceResult& r, const std::string& suffix) const {
    return (std::filesystem::path(dir_) / (r.cache_key + suffix)).string();
  }

  std::string dir_;
};

TEST_F(ReferenceCache, SecondCallIsServedFromDiskWithIdenticalPixels) {
  const ReferenceResult first = cached(scene(), request());
  EXPECT_FALSE(first.from_cache);
  for (const char* suffix : {".exr", ".a.exr", ".b.exr", ".json"})
    EXPECT_TRUE(std::filesystem::exists(path_of(first, suffix))) << suffix;
  const ReferenceResult second = cached(scene(), request());
  EXPECT_TRUE(second.from_cache);
  EXPECT_EQ(second.cache_key, first.cache_key);
  EXPECT_EQ(second.image.pixels, first.image.pixels);
  EXPECT_EQ(second.half_a.pixels, first.half_a.pixels);
  EXPECT_EQ(second.half_b.pixels, first.half_b.pixels);
  EXPECT_EQ(second.spp_total, first.spp_total);
  EXPECT_DOUBLE_EQ(second.noise_mse, first.noise_mse);
  EXPECT_DOUBLE_EQ(second.render_seconds, first.render_seconds);
}

TEST_F(ReferenceCache, ThreadsAndProgressDoNotChangeTheKey) {
  cached(scene(), request());
  AoReferenceRequest other = request();
  other.threads = 1;
  other.progress = true;
  EXPECT_TRUE(cached(scene(), other).from_cache);
}

TEST_F(ReferenceCache, EveryKeyInputMisses) {
  const ReferenceResult base = cached(scene(), request());
  auto expect_miss = [&](const Scene& s, const AoReferenceRequest& r, const char* what) {
    const ReferenceResult result = cached(s, r);
    EXPECT_FALSE(result.from_cache) << what;
    EXPECT_NE(result.cache_key, base.cache_key) << what;
  };
  AoReferenceRequest r = request();
  r.spp.spp_per_half = 16;
  expect_miss(scene(), r, "spp");
  r = request();
  r.seed = 2;
  expect_miss(scene(), r, "seed");
  r = request();
  r.width = 24;
  expect_miss(scene(), r, "width");
  r = request();
  r.height = 8;
  expect_miss(scene(), r, "height");
  r = request();
  r.spp.spp_per_half = 0;
  r.spp.target_noise_mse = 1e-2;
  r.spp.max_spp_per_half = 16;
  expect_miss(scene(), r, "automatic spp");
  r.spp.target_noise_mse = 2e-2;
  expect_miss(scene(), r, "automatic spp target");
  r = request();
  r.ao = scene().ao;
  r.ao->d_max = 1.5f;
  expect_miss(scene(), r, "d_max override");
  Scene s = scene();
  s.ao.d_max = 1.5f;
  expect_miss(s, request(), "scene d_max");
  s = scene();
  s.ao.falloff_exponent = 1.0f;
  expect_miss(s, request(), "falloff exponent");
  s = scene();
  s.ao.attenuated = false;
  expect_miss(s, request(), "attenuation");
  expect_miss(scene(1.1), request(), "geometry");
  s = scene();
  s.camera.eye.y *= 0.5f;
  expect_miss(s, request(), "camera");
  EXPECT_TRUE(cached(scene(), request()).from_cache);  // the first entry is still there
}

TEST_F(ReferenceCache, CorruptSidecarIsNotUsedAndIsRepaired) {
  const ReferenceResult first = cached(scene(), request());
  std::ofstream(path_of(first, ".json"), std::ios::trunc) << "{\"key\": \"trunc";
  const ReferenceResult second = cached(scene(), request());
  EXPECT_FALSE(second.from_cache);
  EXPECT_EQ(second.image.pixels, first.image.pixels);  // re-rendered, deterministically
  EXPECT_TRUE(cached(scene(), request()).from_cache);  // and written back
}

TEST_F(ReferenceCache, SidecarWithOtherInputsIsNotUsed) {
  // As after a hash collision or a hand-edited file: the sidecar names other inputs.
  const ReferenceResult first = cached(scene(), request());
  std::ifstream in(path_of(first, ".json"));
  nlohmann::json sidecar = nlohmann::json::parse(in);
  in.close();
  sidecar["inputs"]["seed"] = 99;
  std::ofstream(path_of(first, ".json"), std::ios::trunc) << sidecar.dump();
  EXPECT_FALSE(cached(scene(), request()).from_cache);
}

TEST_F(ReferenceCache, CorruptOrMissingImageIsNotUsed) {
  const ReferenceResult first = cached(scene(), request());
  {
    // Flip bytes in the middle of the reference EXR (the file may or may not still decode).
    std::fstream file(path_of(first, ".exr"), std::ios::in | std::ios::out | std::ios::binary);
    const auto size = std::filesystem::file_size(path_of(first, ".exr"));
    file.seekp(std::streamoff(size / 2));
    const char garbage[8] = {1, 2, 3, 4, 5, 6, 7, 8};
    file.write(garbage, sizeof garbage);
  }
  EXPECT_FALSE(cached(scene(), request()).from_cache);
  EXPECT_TRUE(cached(scene(), request()).from_cache);
  // A half image replaced by another valid image of the same shape.
  std::filesystem::copy_file(path_of(first, ".a.exr"), path_of(first, ".b.exr"),
                             std::filesystem::copy_options::overwrite_existing);
  EXPECT_FALSE(cached(scene(), request()).from_cache);
  std::filesystem::remove(path_of(first, ".a.exr"));
  EXPECT_FALSE(cached(scene(), request()).from_cache);
}

TEST_F(ReferenceCache, RendererVersionIsPartOfTheKey) {
  const nlohmann::json inputs = ao_reference_inputs(scene(), request());
  EXPECT_EQ(inputs.at("renderer_version"), kAoReferenceVersion);
  EXPECT_EQ(inputs.at("pass"), "ao");
  nlohmann::json older = inputs;
  older["renderer_version"] = kAoReferenceVersion - 1;
  EXPECT_NE(reference_cache_key(older), reference_cache_key(inputs));
}

// Issue 19, item 6: pixel corruption was detected and re-rendered, but an edited noise_mse
// in an entry's sidecar was used as it stood (mse_over_noise 4.7e9 instead of 156.7).
TEST_F(ReferenceCache, EditedMetadataIsAMissNotAResult) {
  const Scene planes = scene();
  const ReferenceResult first = cached(planes, request());
  ASSERT_FALSE(first.from_cache);
  ASSERT_TRUE(cached(planes, request()).from_cache);
  const std::string sidecar = path_of(first, ".json");
  const nlohmann::json original = nlohmann::json::parse(test::read_text(sidecar));
  ASSERT_TRUE(original.contains("checksum"));
  for (const char* key : {"noise_mse", "spp_total", "noise_target_met", "render_seconds"}) {
    nlohmann::json edited = original;
    if (std::string(key) == "noise_mse") edited[key] = original[key].get<double>() * 1e-7;
    else if (std::string(key) == "noise_target_met") edited[key] = !original[key].get<bool>();
    else edited[key] = original[key].get<double>() + 1;
    std::ofstream(sidecar) << edited.dump(2);
    const ReferenceResult again = cached(planes, request());
    EXPECT_FALSE(again.from_cache) << key << ": an edited entry was used";
    EXPECT_DOUBLE_EQ(again.noise_mse, first.noise_mse) << key;
    EXPECT_EQ(again.spp_total, first.spp_total) << key;
    // Rendered again and stored whole: the next request is a hit with the true metadata.
    const ReferenceResult hit = cached(planes, request());
    EXPECT_TRUE(hit.from_cache) << key;
    EXPECT_DOUBLE_EQ(hit.noise_mse, first.noise_mse) << key;
  }
  // An entry without a checksum (an older build's) is rendered again too.
  nlohmann::json old = original;
  old.erase("checksum");
  std::ofstream(sidecar) << old.dump(2);
  EXPECT_FALSE(cached(planes, request()).from_cache);
}

}  // namespace
}  // namespace ldm
