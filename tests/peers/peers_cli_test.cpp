// `ldmbench run` and `ldmbench sweep` with the GTAO and GPU RTAO peers: `--pass gtao,rtao_gpu`
// and a sweep file's passes axis make records like the other peers' (structure none), with
// their parameters and counts as described columns, images and a scored reference.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <set>

#include <nlohmann/json.hpp>

#include "harness/settings/record_schema.h"
#include "support/test_support.h"

namespace ldm {
namespace {

namespace fs = std::filesystem;

void expect_peer_records(const nlohmann::json& records, const fs::path& out) {
  std::set<std::string> passes;
  for (const auto& r : records) {
    EXPECT_EQ(r["status"], "ok") << r["status_detail"];
    EXPECT_EQ(r["structure"], "none");
    const std::string pass = r["pass"];
    passes.insert(pass);
    for (const char* key : {"frame_ms_median", "mse", "mssim", "ref_noise_mse", "covered_pixel_fraction"})
      EXPECT_TRUE(r.contains(key) && r[key].is_number()) << pass << " " << key;
    if (pass == "gtao") {
      EXPECT_EQ(r["gtao_slices"], 2);
      EXPECT_TRUE(r["gtao_ms_median"].is_number());
      EXPECT_TRUE(r["gbuffer_ms_median"].is_number());
    } else {
      EXPECT_EQ(r["rtao_gpu_spp"], 2);
      EXPECT_EQ(r["rtao_gpu_primary"], "trace");
      for (const char* key : {"rtao_gpu_primary_ms_median", "rtao_gpu_ms_median", "rtao_gpu_bvh_ms", "rtao_gpu_bvh_bytes",
                              "work_rtao_gpu_primary_nodes_mean", "rtao_gpu_primary_steps_max",
                              "work_rtao_gpu_nodes_mean", "work_rtao_gpu_nodes_max",
                              "work_rtao_gpu_triangles_mean", "work_rtao_gpu_triangles_max",
                              "rtao_gpu_steps_max", "mem_bvh_nodes_allocated"})
        EXPECT_TRUE(r.contains(key) && r[key].is_number()) << key;
      EXPECT_GE(r["work_rtao_gpu_nodes_mean"].get<double>(), 1.0);
    }
    EXPECT_TRUE(fs::exists(out / r["image_exr"].get<std::string>()));
    for (const auto& [key, value] : r.items()) EXPECT_NE(find_column(key), nullptr) << key;
  }
  EXPECT_EQ(passes, (std::set<std::string>{"gtao", "rtao_gpu"}));
}

TEST(PeersCli, RunTakesBothPasses) {
  const fs::path out = fs::path(test::make_temp_dir("ldm-peers")) / "run";
  const std::string cache = test::make_temp_dir("ldm-peers-cache");
  const test::Outcome run = test::ldmbench(
      "run --scene cornell --pass gtao,rtao_gpu --param gtao:slices=2 --param rtao_gpu:spp=2 "
      "--width 24 --height 24 --frames 1 --time-target 0 --warmup 1 --reference-spp 8 --cache-dir " + cache +
      " --out " + out.string() + " 2>&1");
  ASSERT_EQ(run.status, 0) << run.output;
  const auto json = nlohmann::json::parse(test::read_text(out / "records.json"));
  ASSERT_EQ(json["records"].size(), 2u);
  expect_peer_records(json["records"], out);
}

TEST(PeersCli, SweepFileTakesBothPasses) {
  const fs::path dir = test::make_temp_dir("ldm-peers-sweep");
  std::ofstream(dir / "peers.json") << R"({
    "axes": {"scenes": ["cornell"], "passes": ["gtao", "rtao_gpu"], "image_size": "24x24",
             "frames": 1, "warmup": 0, "gtao:slices": 2, "rtao_gpu:spp": 2},
    "settings": {"reference": {"spp": 8}}
  })";
  const test::Outcome run = test::ldmbench("sweep " + (dir / "peers.json").string() +
                                           " --cache-dir " + (dir / "cache").string() +
                                           " --out " + (dir / "run").string() + " 2>&1");
  ASSERT_EQ(run.status, 0) << run.output;
  const auto json = nlohmann::json::parse(test::read_text(dir / "run" / "records.json"));
  ASSERT_EQ(json["records"].size(), 2u);
  expect_peer_records(json["records"], dir / "run");
}

// A traversal the device's loop limit cuts short is an invalid record, saying why.
TEST(PeersCli, RtaoGpuPastTheLoopLimitIsInvalid) {
  const fs::path dir = test::make_temp_dir("ldm-peers-limit");
  const test::Outcome run = test::ldmbench(
      "run --scene plane --pass rtao_gpu --param rtao_gpu:spp=40000 --width 16 --height 16 "
      "--frames 1 --time-target 0 --warmup 0 --no-reference --out " + (dir / "run").string() + " 2>&1");
  const auto json = nlohmann::json::parse(test::read_text(dir / "run" / "records.json"));
  ASSERT_EQ(json["records"].size(), 1u) << run.output;
  const auto& r = json["records"][0];
  if (r["loop_iteration_limit"] == 0) GTEST_SKIP() << "this device has no known loop limit";
  EXPECT_EQ(r["status"], "invalid");
  EXPECT_NE(r["status_detail"].get<std::string>().find("cut short"), std::string::npos) << r["status_detail"];
}

}  // namespace
}  // namespace ldm
