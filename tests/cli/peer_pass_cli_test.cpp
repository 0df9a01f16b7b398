// `ldmbench run --pass hbao`: a pass that reads no LDM runs once per scene and AO setting
// (structure none, whatever --structure says), with its own parameters through --param.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "support/test_support.h"

namespace ldm {
namespace {

namespace fs = std::filesystem;

TEST(PeerPassCli, HbaoRecordIsCompleteAndScored) {
  const fs::path out = fs::path(test::make_temp_dir("ldm-peer")) / "run";
  const std::string cache = test::make_temp_dir("ldm-peer-cache");
  std::string output;
  const int status = test::run_command(
      std::string(LDM_BINARY_PATH) +
          " run --scene cornell --structure psppsll,dfbuffer --pass hbao --param hbao:steps=4 "
          "--width 32 --height 32 --frames 2 --warmup 1 --reference-spp 16 --cache-dir " +
          cache + " --out " + out.string() + " 2>&1",
      &output);
  ASSERT_EQ(status, 0) << output;
  std::ifstream in(out / "records.json");
  std::stringstream text;
  text << in.rdbuf();
  const auto json = nlohmann::json::parse(text.str());
  ASSERT_EQ(json["records"].size(), 1u) << "one configuration, not one per structure";
  const auto& r = json["records"][0];
  EXPECT_EQ(r["status"], "ok") << r["status_detail"];
  EXPECT_EQ(r["structure"], "none");
  EXPECT_EQ(r["pass"], "hbao");
  EXPECT_EQ(r["hbao_steps"], 4);
  for (const char* key : {"gbuffer_ms_median", "hbao_ms_median", "frame_ms_median", "mse", "mssim"})
    EXPECT_TRUE(r.contains(key) && r[key].is_number()) << key;
  EXPECT_FALSE(r.contains("build_ms_median")) << "nothing is built";
}

TEST(PeerPassCli, UnknownHbaoParameterIsRejected) {
  std::string output;
  const int status = test::run_command(std::string(LDM_BINARY_PATH) +
                                           " run --scene cornell --pass hbao --param hbao:radius=2 "
                                           "--out /nonexistent/never 2>&1",
                                       &output);
  EXPECT_EQ(status, 2) << output;
  EXPECT_NE(output.find("radius"), std::string::npos) << output;
}

}  // namespace
}  // namespace ldm
