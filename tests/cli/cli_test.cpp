// `ldmbench run` end to end: the main job writes records and images; bad input gets a clear
// error, a nonzero exit and no output folder; a failing configuration in a sweep is recorded
// as failed while the sweep goes on.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "support/test_support.h"

namespace ldm {
namespace {

namespace fs = std::filesystem;

struct Outcome {
  int status;
  std::string output;
};

Outcome ldmbench(const std::string& args) {
  Outcome o;
  o.status = test::run_command(std::string(LDM_BINARY_PATH) + " " + args, &o.output);
  return o;
}

std::string read_text(const fs::path& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// Bad input: exit status 2, a message naming the culprit, and nothing written.
void expect_rejected(const std::string& args, const std::string& culprit) {
  const fs::path out = fs::path(test::make_temp_dir("ldm-cli")) / "out";
  const Outcome o = ldmbench("run " + args + " --out " + out.string());
  EXPECT_EQ(o.status, 2) << args << "\n" << o.output;
  EXPECT_NE(o.output.find(culprit), std::string::npos) << args << "\n" << o.output;
  EXPECT_FALSE(fs::exists(out)) << args << ": an output folder was created";
}

TEST(Cli, MainJobWritesRecordsAndImages) {
  const fs::path out = fs::path(test::make_temp_dir("ldm-cli")) / "run";
  const Outcome o = ldmbench("run --scene cornell --structure psppsll --pass ao -N 4 -R 32 "
                             "--width 48 --height 40 --frames 2 --warmup 1 --out " + out.string());
  ASSERT_EQ(o.status, 0) << o.output;
  EXPECT_NE(o.output.find("records: "), std::string::npos);
  const auto json = nlohmann::json::parse(read_text(out / "records.json"));
  ASSERT_EQ(json["records"].size(), 1u);
  const auto& r = json["records"][0];
  EXPECT_EQ(r["status"], "ok") << r["status_detail"];
  EXPECT_EQ(r["scene"], "cornell");
  EXPECT_EQ(r["structure"], "psppsll");
  EXPECT_EQ(r["n_views"], 4);
  EXPECT_EQ(r["r_ldm"], 32);
  EXPECT_FALSE(r["device"].get<std::string>().empty());
  EXPECT_GT(r["fragments"].get<int64_t>(), 0);
  EXPECT_EQ(r["fragments_stored"], r["fragments"]);
  EXPECT_EQ(r["fragments_lost"], 0);
  EXPECT_GE(r["max_depth_complexity"].get<int>(), 2);
  for (const char* key : {"construct_ms_median", "construct_ms_min", "construct_ms_max",
                          "clear_ms_median", "ao_ms_median", "gbuffer_ms_median",
                          "raster_baseline_ms_median", "build_ms_median"})
    EXPECT_TRUE(r.contains(key) && r[key].is_number()) << key;
  EXPECT_LE(r["construct_ms_min"].get<double>(), r["construct_ms_median"].get<double>());
  EXPECT_LE(r["construct_ms_median"].get<double>(), r["construct_ms_max"].get<double>());
  // Memory: heads N*R^2*4 bytes, nodes 8 bytes per fragment, all used.
  EXPECT_EQ(r["mem_heads_allocated"], 4 * 32 * 32 * 4);
  EXPECT_EQ(r["mem_nodes_used"].get<int64_t>(), 8 * r["fragments"].get<int64_t>());
  EXPECT_GE(r["bytes_allocated"].get<int64_t>(), r["bytes_used"].get<int64_t>());
  // Images exist at paths relative to the record file.
  const fs::path exr = out / r["image_exr"].get<std::string>();
  const fs::path png = out / r["image_png"].get<std::string>();
  EXPECT_TRUE(fs::is_regular_file(exr)) << exr;
  EXPECT_TRUE(fs::is_regular_file(png)) << png;
  EXPECT_TRUE(fs::path(r["image_exr"].get<std::string>()).is_relative());
  // The CSV has the same row.
  const std::string csv = read_text(out / "records.csv");
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 2);
  EXPECT_EQ(csv.rfind("config_id,status,", 0), 0u);
}

TEST(Cli, SweepRecordsAFailedConfigurationAndGoesOn) {
  // A resolution whose pixels alone exceed the device's storage block fails; the next runs.
  const int64_t block = test::gl_context().device().max_ssbo_block_bytes;
  const int n = 64;
  const int too_big = int(std::ceil(std::sqrt(double(block) / 4.0 / n))) + 1;
  ASSERT_LE(too_big, 8192);
  const fs::path out = fs::path(test::make_temp_dir("ldm-cli")) / "sweep";
  const Outcome o = ldmbench("run --scene cornell -N " + std::to_string(n) + " -R " +
                             std::to_string(too_big) + ",16 --width 32 --height 32 --frames 1 "
                             "--warmup 0 --out " + out.string());
  EXPECT_EQ(o.status, 3) << o.output;
  const auto json = nlohmann::json::parse(read_text(out / "records.json"));
  ASSERT_EQ(json["records"].size(), 2u);
  EXPECT_EQ(json["records"][0]["status"], "failed");
  EXPECT_NE(json["records"][0]["status_detail"].get<std::string>().find("GL_MAX_SHADER_STORAGE_BLOCK_SIZE"),
            std::string::npos);
  EXPECT_EQ(json["records"][1]["status"], "ok");
}

TEST(Cli, LossyConfigurationIsFlaggedNotPassedOff) {
  const fs::path out = fs::path(test::make_temp_dir("ldm-cli")) / "lossy";
  const Outcome o = ldmbench("run --scene cornell -N 4 -R 32 --width 32 --height 32 --frames 1 "
                             "--warmup 0 --param psppsll:pool=fixed --param psppsll:capacity=1000 "
                             "--out " + out.string());
  EXPECT_EQ(o.status, 0) << o.output;
  const auto r = nlohmann::json::parse(read_text(out / "records.json"))["records"][0];
  EXPECT_EQ(r["status"], "lossy");
  EXPECT_TRUE(r["overflow"].get<bool>());
  EXPECT_EQ(r["fragments_lost"].get<int64_t>(), r["fragments"].get<int64_t>() - 1000);
}

TEST(Cli, BadInputIsRejectedBeforeAnythingIsWritten) {
  const std::string dir = test::make_temp_dir("ldm-cli");
  const std::string missing = (fs::path(dir) / "nothere.json").string();
  expect_rejected("--scene " + missing, "nothere.json");
  std::ofstream(fs::path(dir) / "broken.json") << "{\n \"generator\": {\"type\": \"cornell\"\n";
  expect_rejected("--scene " + (fs::path(dir) / "broken.json").string(), "broken.json");
  expect_rejected("--scene cornell -N 0", "--views");
  expect_rejected("--scene cornell -R 0", "--r-ldm");
  expect_rejected("--scene cornell --width 5", "--width");
  expect_rejected("--scene cornell --frames 0", "--frames");
  expect_rejected("--scene cornell --d-max -1", "--d-max");
  expect_rejected("--scene cornell --structure linkedlist", "linkedlist");
  expect_rejected("--scene cornell --pass gi", "gi");
  expect_rejected("--scene cornell --param psppsll", "STRUCTURE:KEY=VALUE");
  expect_rejected("--scene cornell --param psppsll:pool=huge", "pool");
  expect_rejected("--scene cornell --param psppsll:colour=red", "colour");
  expect_rejected("--scene cornell --visibility sometimes", "--visibility");
  expect_rejected("--scene nosuchscene", "nosuchscene");
}

TEST(Cli, HelpDocumentsEveryRunOption) {
  const Outcome o = ldmbench("run --help");
  EXPECT_EQ(o.status, 0);
  for (const char* option : {"--scene", "--structure", "--pass", "--views", "--r-ldm", "--width",
                             "--height", "--d-max", "--frames", "--warmup", "--out", "--param"})
    EXPECT_NE(o.output.find(option), std::string::npos) << option;
}

}  // namespace
}  // namespace ldm
