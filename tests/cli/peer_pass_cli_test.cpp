// `ldmbench run --pass hbao`: a pass that reads no LDM runs once per scene and AO setting
// (structure none, whatever --structure says), with its own parameters through --param.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "support/run_records.h"

namespace ldm {
namespace {

namespace fs = std::filesystem;

TEST(PeerPassCli, HbaoRecordIsCompleteAndScored) {
  const nlohmann::json records =
      test::run_records("peer", "--scene cornell --structure psppsll,dfbuffer --pass hbao --param hbao:steps=4 "
                                "--param hbao:blur=0,2 --width 32 --height 32 --frames 2 --time-target 0 --warmup 1 --reference-spp 16")
          .records;
  ASSERT_EQ(records.size(), 2u) << "one configuration per blur, not one per structure";
  for (size_t i = 0; i < 2; ++i) {
    const auto& r = records[i];
    EXPECT_EQ(r["status"], "ok") << r["status_detail"];
    EXPECT_EQ(r["structure"], "none");
    EXPECT_EQ(r["pass"], "hbao");
    EXPECT_EQ(r["hbao_steps"], 4);
    EXPECT_EQ(r["hbao_blur"], i == 0 ? 0 : 2);
    for (const char* key : {"gbuffer_ms_median", "hbao_ms_median", "frame_ms_median", "mse", "mssim"})
      EXPECT_TRUE(r.contains(key) && r[key].is_number()) << key;
    EXPECT_EQ(r.contains("blur_ms_median"), i == 1) << "the blur is a timed sub-pass";
    EXPECT_FALSE(r.contains("build_ms_median")) << "nothing is built";
    // Its render targets: G-buffer (16 + 16 + 4 bytes a pixel), AO 4, the blur's scratch 4.
    EXPECT_EQ(r["mem_hbao_ao_allocated"], 32 * 32 * 4);
    EXPECT_EQ(r["bytes_allocated"], 32 * 32 * (i == 0 ? 40 : 44));
    // Only what applies to a pass without structure: no N, R_LDM, trace or sizing.
    EXPECT_EQ(r["config_id"], i == 0 ? "cornell-none-hbao-blur=0-steps=4" : "cornell-none-hbao-blur=2-steps=4");
    EXPECT_EQ(r["sizing_policy"], "none");
  }
}

// A comma list in --param is an axis; rtao's time is CPU wall time on the CPU.
TEST(PeerPassCli, RtaoSppAxisRecordsCpuTime) {
  const nlohmann::json records =
      test::run_records("peer-rtao", "--scene cornell --pass rtao --param rtao:spp=1,4 --param rtao:threads=1 "
                                     "--width 32 --height 32 --frames 2 --time-target 0 --warmup 0 --reference-spp 64")
          .records;
  ASSERT_EQ(records.size(), 2u) << "one configuration per spp";
  for (size_t i = 0; i < 2; ++i) {
    const auto& r = records[i];
    EXPECT_EQ(r["status"], "ok") << r["status_detail"];
    EXPECT_EQ(r["config_id"], i == 0 ? "cornell-none-rtao-spp=1-threads=1" : "cornell-none-rtao-spp=4-threads=1");
    EXPECT_EQ(r["rtao_spp"], i == 0 ? 1 : 4);
    EXPECT_EQ(r["timer"], "cpu_wall");
    EXPECT_EQ(r["device"].get<std::string>().rfind("CPU: ", 0), 0u) << r["device"];
    EXPECT_EQ(r["rtao_threads"], 1);
    for (const char* key : {"rtao_ms_median", "frame_ms_median", "mse", "mssim", "rtao_bvh_ms"})
      EXPECT_TRUE(r.contains(key) && r[key].is_number()) << key;
    EXPECT_FALSE(r.contains("gbuffer_ms_median")) << "nothing is drawn";
  }
  EXPECT_LT(records[1]["mse"].get<double>(), records[0]["mse"].get<double>());
}

TEST(PeerPassCli, EmptyItemInAParameterListIsRejected) {
  test::expect_contains(test::refused_run("--scene cornell --pass hbao --param hbao:steps=4,,8"), {"hbao:steps=4,,8"});
}

TEST(PeerPassCli, UnknownHbaoParameterIsRejected) {
  test::expect_contains(test::refused_run("--scene cornell --pass hbao --param hbao:radius=2"), {"radius"});
}

}  // namespace
}  // namespace ldm
