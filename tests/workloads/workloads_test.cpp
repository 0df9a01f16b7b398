// Real scenes end to end (issue 22), through `ldmbench run`: the depth-complexity profile in
// every record, degenerate measurements flagged and never ranked, a mesh file as --scene, a
// trace llvmpipe's loop limiter could cut short recorded invalid, a refusal at the storage
// block that says what would fit (and what it says runs), the real-world scenes of
// assimp-testmodels (skipped, saying so, where the package is missing) and the thesis's two
// workloads. Small: N <= 64, R_LDM <= 128, images of 16-48 pixels, one frame.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <regex>
#include <sstream>

#include "support/test_support.h"

namespace ldm {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using test::Outcome;

const fs::path kModels = "/usr/share/assimp/models";
const fs::path kScenes = fs::path(LDM_TEST_SOURCE_DIR) / ".." / "scenes";

using test::write_file;

// Runs `ldmbench run ARGS --out <fresh>`; returns the records (and the output on failure).
struct RunResult {
  Outcome outcome;
  json records;
  fs::path out;
};
RunResult run(const std::string& args) {
  RunResult r;
  r.out = fs::path(test::make_temp_dir("ldm-workloads")) / "run";
  // Exactly one measured frame (no time target): these tests judge what a run records, not its time.
  r.outcome = test::ldmbench("run " + args + " --frames 1 --warmup 0 --time-target 0 --out " + r.out.string());
  const std::string text = test::read_text((r.out / "records.json").string());
  if (!text.empty()) r.records = json::parse(text)["records"];
  return r;
}

const json& by_structure(const json& records, const std::string& structure) {
  for (const auto& r : records)
    if (r["structure"] == structure) return r;
  static const json none;
  ADD_FAILURE() << "no record of " << structure;
  return none;
}

// "1:812;2-3:340" -> total pixels.
uint64_t histogram_pixels(const std::string& text) {
  uint64_t total = 0;
  std::stringstream in(text);
  for (std::string bin; std::getline(in, bin, ';');) total += std::stoull(bin.substr(bin.find(':') + 1));
  return total;
}

// A floor and a stack of `layers` squares 1 unit thick, 10 wide, as an OBJ; the camera below
// it looking up sees the lowest square, which is the last of every LDM view's list (the views
// look down, harness/views/sphere_partition.h): each trace walks every layer in every view.
std::string deep_stack_scene(const fs::path& dir, int layers, double size = 10.0) {
  std::string obj;
  for (int i = 0; i < layers; ++i) {
    const double y = double(i) / double(layers);
    const double h = size / 2;
    obj += "v " + std::to_string(-h) + " " + std::to_string(y) + " " + std::to_string(-h) + "\n";
    obj += "v " + std::to_string(h) + " " + std::to_string(y) + " " + std::to_string(-h) + "\n";
    obj += "v " + std::to_string(h) + " " + std::to_string(y) + " " + std::to_string(h) + "\n";
    obj += "v " + std::to_string(-h) + " " + std::to_string(y) + " " + std::to_string(h) + "\n";
    const int b = 4 * i + 1;
    obj += "f " + std::to_string(b) + " " + std::to_string(b + 1) + " " + std::to_string(b + 2) + " " +
           std::to_string(b + 3) + "\n";
  }
  write_file(dir, "stack.obj", obj);
  // A spot below too: its photons start on the lowest square and walk every layer as well.
  return write_file(dir, "stack.json", R"({"name": "stack", "meshes": [{"file": "stack.obj"}],
      "camera": {"eye": [0.5, -6, 0.3], "target": [0, 0.5, 0], "fov_y_deg": 30},
      "light": {"position": [0.2, -5, 0.1], "direction": [0, 1, 0], "intensity": 30,
                "inner_angle_deg": 20, "outer_angle_deg": 30},
      "ao": {"d_max": 4.0}})");
}

TEST(Workloads, EveryRecordCarriesTheDepthComplexityProfile) {
  const RunResult r = run("--scene cornell --structure psppsll,ppfla --param ppfla:k=3 -N 4 -R 32 "
                    "--width 32 --height 32 --no-reference");
  ASSERT_EQ(r.outcome.status, 0) << r.outcome.output;
  for (const auto& record : r.records) {
    SCOPED_TRACE(record["config_id"].get<std::string>());
    const auto p50 = record["depth_p50"].get<int>(), p90 = record["depth_p90"].get<int>(),
               p99 = record["depth_p99"].get<int>(), max = record["max_depth_complexity"].get<int>();
    EXPECT_GE(p50, 1);
    EXPECT_LE(p50, p90);
    EXPECT_LE(p90, p99);
    EXPECT_LE(p99, max);
    // The histogram counts every non-empty LDM pixel once.
    const double pixels = 4.0 * 32 * 32 * record["nonempty_pixel_fraction"].get<double>();
    EXPECT_EQ(histogram_pixels(record["depth_histogram"]), uint64_t(std::llround(pixels)));
    EXPECT_GT(record["scene_radius"].get<double>(), 1.0);
    EXPECT_EQ(record["d_max_source"], "generator cornell");
    EXPECT_EQ(record["camera_source"], "generator cornell");
  }
  // The fixed array's k = 3 against the Cornell box's 6-deep pixels: what lies above k is
  // what it lost.
  const json& ppfla = by_structure(r.records, "ppfla");
  EXPECT_EQ(ppfla["status"], "lossy");
  EXPECT_GT(ppfla["depth_share_above_k"].get<double>(), 0.0);
  EXPECT_LT(ppfla["depth_share_above_k"].get<double>(), 1.0);
  EXPECT_FALSE(by_structure(r.records, "psppsll").contains("depth_share_above_k"));
}

TEST(Workloads, DegenerateMeasurementsAreFlaggedAndNeverRanked) {
  const fs::path dir = test::make_temp_dir("ldm-workloads");
  // A box in millimetres with d_max 1 mm: no ray finds an occluder within reach, so the
  // reference is AO = 1 everywhere, without noise (the engine of issue 22, in miniature), and
  // the AO range is a fraction of an LDM pixel.
  write_file(dir, "box.off", test::cube_off(400));
  const std::string tiny = write_file(dir, "tiny.json", R"({"name": "tiny-dmax", "meshes": [{"file": "box.off"}], "ao": {"d_max": 1}})");
  // The camera turned away from everything.
  const std::string away = write_file(dir, "away.json", R"({"name": "away", "meshes": [{"file": "box.off"}],
      "camera": {"eye": [200, 200, -2000], "target": [200, 200, -4000]}})");
  const std::string cache = test::make_temp_dir("ldm-cache");
  const RunResult r = run("--scene " + tiny + "," + away + ",cornell -N 4 -R 32 --width 24 --height 24 "
                    "--reference-spp 16 --cache-dir " + cache);
  ASSERT_EQ(r.outcome.status, 0) << r.outcome.output;
  ASSERT_EQ(r.records.size(), 3u);
  for (const auto& record : r.records) {
    const std::string scene = record["scene_name"], degenerate = record["degenerate"];
    SCOPED_TRACE(scene + ": " + degenerate);
    if (scene == "tiny-dmax") {
      EXPECT_EQ(record["ref_noise_mse"].get<double>(), 0.0);
      EXPECT_NE(degenerate.find("reference without noise"), std::string::npos);
      EXPECT_LT(record["d_max_ldm_pixels"].get<double>(), 3.0);
      EXPECT_NE(degenerate.find("LDM pixels"), std::string::npos);
    } else if (scene == "away") {
      EXPECT_EQ(record["covered_pixel_fraction"].get<double>(), 0.0);
      EXPECT_NE(degenerate.find("sees no surface"), std::string::npos);
    } else {
      EXPECT_EQ(degenerate, "");  // a real measurement
      EXPECT_GT(record["covered_pixel_fraction"].get<double>(), 0.5);
      EXPECT_GT(record["d_max_ldm_pixels"].get<double>(), 3.0);
    }
    if (!degenerate.empty())
      EXPECT_NE(record["status_detail"].get<std::string>().find("degenerate: "), std::string::npos);
  }
  // The report lists them as flagged and ranks only the Cornell box.
  const Outcome report = test::ldmbench("report " + r.out.string());
  ASSERT_EQ(report.status, 0) << report.output;
  const std::string summary = test::read_text((r.out / "report" / "summary.md").string());
  const auto best = summary.find("## Best"), flagged = summary.find("## Flagged");
  ASSERT_NE(best, std::string::npos) << summary;
  ASSERT_NE(flagged, std::string::npos) << summary;
  const std::string best_table = summary.substr(best, flagged > best ? flagged - best : std::string::npos);
  EXPECT_EQ(best_table.find("tiny-dmax-"), std::string::npos) << best_table;
  EXPECT_EQ(best_table.find("away-"), std::string::npos) << best_table;
  EXPECT_NE(best_table.find("cornell-"), std::string::npos) << best_table;
  const std::string flagged_table = summary.substr(flagged);
  EXPECT_NE(flagged_table.find("tiny-dmax-"), std::string::npos) << flagged_table;
  EXPECT_NE(flagged_table.find("away-"), std::string::npos) << flagged_table;
  // One depth histogram per scene (the camera turned away still has LDMs and a census).
  const auto histograms = summary.find("Panels: ");
  ASSERT_NE(histograms, std::string::npos) << summary;
  const std::string panels = summary.substr(histograms, summary.find('\n', histograms) - histograms);
  // Panel titles follow the report's one scheme: "scene, settings" (scripts/report/ldmreport/style.py).
  for (const char* scene : {"tiny-dmax, N=4, R_LDM=32", "away, N=4, R_LDM=32", "cornell, N=4, R_LDM=32"})
    EXPECT_NE(panels.find(scene), std::string::npos) << panels;
}

// The error over the covered pixels on a model that covers part of the image: the
// background is the same in both images, so mse is mse_covered scaled by the covered share;
// the console shows the columns with which way is better.
TEST(Workloads, ErrorOverTheCoveredPixels) {
  const fs::path dir = test::make_temp_dir("ldm-workloads");
  write_file(dir, "tri.ply", "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
                             "property float z\nelement face 2\nproperty list uchar int vertex_indices\n"
                             "end_header\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 1 2\n3 0 2 3\n");
  const RunResult r = run("--scene " + (dir / "tri.ply").string() + " -N 4 -R 32 --width 32 --height 32 "
                          "--reference-spp 16 --cache-dir " + test::make_temp_dir("ldm-cache"));
  ASSERT_EQ(r.outcome.status, 0) << r.outcome.output;
  const json& record = r.records.at(0);
  const double covered = record["covered_pixel_fraction"].get<double>();
  ASSERT_GT(covered, 0.0);
  ASSERT_LT(covered, 1.0);
  EXPECT_GT(record["mse_covered"].get<double>(), record["mse"].get<double>());
  EXPECT_NEAR(record["mse_covered"].get<double>() * covered, record["mse"].get<double>(),
              1e-12 + 1e-9 * record["mse"].get<double>());
  EXPECT_TRUE(record.contains("nrmse_covered"));
  EXPECT_NE(record["mssim_covered"].get<double>(), record["mssim"].get<double>());
  EXPECT_NE(r.outcome.output.find("MSE covered ↓"), std::string::npos) << r.outcome.output;
  EXPECT_NE(r.outcome.output.find("MSSIM covered ↑"), std::string::npos) << r.outcome.output;
}

TEST(Workloads, AMeshFileIsAScene) {
  const fs::path dir = test::make_temp_dir("ldm-workloads");
  write_file(dir, "tri.ply", "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
                             "property float z\nelement face 2\nproperty list uchar int vertex_indices\n"
                             "end_header\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 1 2\n3 0 2 3\n");
  const RunResult r = run("--scene " + (dir / "tri.ply").string() + " -N 4 -R 32 --width 24 --height 24 --no-reference");
  ASSERT_EQ(r.outcome.status, 0) << r.outcome.output;
  const json& record = r.records.at(0);
  EXPECT_EQ(record["status"], "ok") << record["status_detail"];
  EXPECT_EQ(record["scene_name"], "tri");
  EXPECT_EQ(record["config_id"].get<std::string>().rfind("tri-psppsll-ao-", 0), 0u);
  EXPECT_EQ(record["triangles"], 2);
  EXPECT_NE(record["camera_source"].get<std::string>().find("derived"), std::string::npos);
  EXPECT_NE(record["d_max_source"].get<std::string>().find("derived"), std::string::npos);
  EXPECT_GT(record["covered_pixel_fraction"].get<double>(), 0.0);
  // A scene file's "name" names its configurations.
  const std::string named = write_file(dir, "scene.json", R"({"name": "corner", "meshes": [{"file": "tri.ply"}]})");
  const RunResult n = run("--scene " + named + " -N 4 -R 32 --width 24 --height 24 --no-reference");
  ASSERT_EQ(n.outcome.status, 0) << n.outcome.output;
  EXPECT_EQ(n.records.at(0)["config_id"].get<std::string>().rfind("corner-psppsll-", 0), 0u);
  // Two scenes of one name are refused before anything runs.
  const std::string twin = write_file(dir, "twin.json", R"({"name": "corner", "generator": {"type": "plane"}})");
  const RunResult both = run("--scene " + named + "," + twin + " -N 4 -R 32 --no-reference");
  EXPECT_EQ(both.outcome.status, 2) << both.outcome.output;
  EXPECT_NE(both.outcome.output.find("both named 'corner'"), std::string::npos) << both.outcome.output;
  EXPECT_FALSE(fs::exists(both.out));
  // A mesh file that does not parse is a clear error, exit 2, nothing written.
  write_file(dir, "broken.ply", "ply\nformat ascii 1.0\nelement vertex 3\nend_header\nnonsense\n");
  const RunResult broken = run("--scene " + (dir / "broken.ply").string() + " --no-reference");
  EXPECT_EQ(broken.outcome.status, 2) << broken.outcome.output;
  EXPECT_NE(broken.outcome.output.find("broken.ply"), std::string::npos) << broken.outcome.output;
  EXPECT_FALSE(fs::exists(broken.out));
  // One that Assimp itself aborts on (found by fuzz_import): the same, never a crash.
  const std::string aborts = test::read_text((fs::path(LDM_TEST_SOURCE_DIR) / "fuzz" / "corpus" / "import" / "assimp-aborts.off").string());
  write_file(dir, "aborts.off", aborts.substr(1));
  const RunResult crash = run("--scene " + (dir / "aborts.off").string() + " --no-reference");
  EXPECT_EQ(crash.outcome.status, 2) << crash.outcome.output;
  EXPECT_NE(crash.outcome.output.find("aborts.off"), std::string::npos) << crash.outcome.output;
  EXPECT_NE(crash.outcome.output.find("crashed"), std::string::npos) << crash.outcome.output;
  EXPECT_FALSE(fs::exists(crash.out));
}

TEST(Workloads, ATraceTheLoopLimiterCouldCutIsInvalid) {
  // 1100 layers: at N = 64 one invocation walks 64 x 1100 list entries, past llvmpipe's 65,535
  // loop iterations; at N = 8 it stays far below.
  const fs::path dir = test::make_temp_dir("ldm-workloads");
  const std::string scene = deep_stack_scene(dir, 1100);
  // The AO trace (one invocation per pixel) and the photon trace (one per light texel).
  const RunResult deep = run("--scene " + scene + " --pass ao,indirect --param indirect:r_light=16 -N 8,64 "
                             "-R 16 --width 16 --height 16 --no-reference");
  ASSERT_EQ(deep.records.size(), 4u) << deep.outcome.output;
  for (const auto& record : deep.records) {
    SCOPED_TRACE(record["config_id"].get<std::string>() + ": " + record["status_detail"].get<std::string>());
    const int n = record["n_views"];
    const auto bound = record["trace_steps_bound"].get<int64_t>();
    const auto most = record["trace_steps_max"].get<int64_t>();
    EXPECT_GE(record["max_depth_complexity"].get<int>(), 1100);
    EXPECT_GE(bound, most);
    // Every view walks the whole stack from the lowest square: an invocation needs more than
    // N x 1000 steps, which it runs where nothing cuts it short.
    const bool limited = record["loop_iteration_limit"].get<int64_t>() > 0;  // llvmpipe
    if (!limited || n == 8) EXPECT_GT(most, int64_t(n) * 1000);
    if (!limited) continue;
    if (n == 64) {
      EXPECT_EQ(record["status"], "invalid");
      EXPECT_NE(record["status_detail"].get<std::string>().find("cut short"), std::string::npos);
      // And the counts show the cut: fewer steps than the walks need, stopped below the limit.
      EXPECT_LT(most, int64_t(n) * 1000);
      EXPECT_LE(most, 65535);
    } else {
      EXPECT_EQ(record["status"], "ok") << record["status_detail"];
      EXPECT_LT(bound, 65535);
    }
  }
  EXPECT_EQ(deep.outcome.status, 3) << "an invalid record makes the exit status 3";
}

TEST(Workloads, ARefusalAtTheStorageBlockSaysWhatFitsAndTheSuggestionRuns) {
  // One deep pile of 1024 thin squares on a floor: a fixed array sized for its deepest pixel (k = 1024
  // entries for every pixel) needs N R^2 k x 4 bytes = 256 MiB at N = 4, R = 128.
  const fs::path dir = test::make_temp_dir("ldm-workloads");
  std::string obj = "v -5 0 -5\nv 5 0 -5\nv 5 0 5\nv -5 0 5\nf 1 2 3 4\n";
  for (int i = 0; i < 1024; ++i) {
    const std::string y = std::to_string(0.1 + i * 0.0005);
    obj += "v -0.5 " + y + " -0.5\nv 0.5 " + y + " -0.5\nv 0.5 " + y + " 0.5\nv -0.5 " + y + " 0.5\n";
    const int b = 5 + 4 * i;
    obj += "f " + std::to_string(b) + " " + std::to_string(b + 1) + " " + std::to_string(b + 2) + " " +
           std::to_string(b + 3) + "\n";
  }
  write_file(dir, "pile.obj", obj);
  const std::string scene = write_file(dir, "pile.json", R"({"name": "pile", "meshes": [{"file": "pile.obj"}]})");
  const std::string small = " --width 16 --height 16 --no-reference";
  const RunResult refused = run("--scene " + scene + " --structure ppfla --sizing oracle -N 4 -R 128" + small);
  ASSERT_EQ(refused.records.size(), 1u) << refused.outcome.output;
  const json& failed = refused.records[0];
  ASSERT_EQ(failed["status"], "failed");
  const std::string detail = failed["status_detail"];
  EXPECT_NE(detail.find("GL_MAX_SHADER_STORAGE_BLOCK_SIZE"), std::string::npos) << detail;
  std::smatch r_fit, k_fit;
  ASSERT_TRUE(std::regex_search(detail, r_fit, std::regex(R"(R_LDM = (\d+) \(at N 4\))"))) << detail;
  ASSERT_TRUE(std::regex_search(detail, k_fit, std::regex(R"(k = (\d+) \(--param ppfla:k=\d+; lossy: [^,]*, (\d+) of (\d+) fragments)")))
      << detail;
  // The suggested R_LDM fits and runs; the suggested k fits, and loses what the census said.
  const RunResult at_r = run("--scene " + scene + " --structure ppfla --sizing oracle -N 4 -R " + r_fit[1].str() + small);
  ASSERT_EQ(at_r.records.size(), 1u) << at_r.outcome.output;
  EXPECT_EQ(at_r.records[0]["status"], "ok") << at_r.records[0]["status_detail"];
  const RunResult at_k = run("--scene " + scene + " --structure ppfla --param ppfla:k=" + k_fit[1].str() + " -N 4 -R 128" + small);
  ASSERT_EQ(at_k.records.size(), 1u) << at_k.outcome.output;
  EXPECT_EQ(at_k.records[0]["status"], "lossy") << at_k.records[0]["status_detail"];
  EXPECT_EQ(at_k.records[0]["fragments_lost"].get<int64_t>(), std::stoll(k_fit[2].str()));
  EXPECT_EQ(at_k.records[0]["fragments"].get<int64_t>(), std::stoll(k_fit[3].str()));
  // The largest of this scene that runs: k = 1025 four-byte entries for each of N R^2 pixels in
  // one block, so R_LDM = floor(sqrt(limit / (16 k))) fits and one more does not.
  std::smatch limit, deepest;
  ASSERT_TRUE(std::regex_search(detail, limit, std::regex(R"(GL_MAX_SHADER_STORAGE_BLOCK_SIZE of (\d+) MiB)")));
  ASSERT_TRUE(std::regex_search(detail, deepest, std::regex(R"(deepest pixel (\d+))")));
  const double block = std::stod(limit[1].str()) * double(1 << 20);
  const auto largest = int(std::floor(std::sqrt(block / (4.0 * 4.0 * std::stod(deepest[1].str())))));
  const RunResult edge = run("--scene " + scene + " --structure ppfla --sizing oracle -N 4 -R " +
                             std::to_string(largest) + "," + std::to_string(largest + 1) + small);
  ASSERT_EQ(edge.records.size(), 2u) << edge.outcome.output;
  for (const auto& record : edge.records)
    EXPECT_EQ(record["status"], record["r_ldm"] == largest ? "ok" : "failed") << record["config_id"];
}

TEST(Workloads, RealWorldScenesRunAndSpanDepthProfiles) {
  if (!fs::is_directory(kModels))
    GTEST_SKIP() << "assimp-testmodels is not installed (" << kModels
                 << " is missing): scripts/setup.sh installs it; scenes/engine.json and the "
                    "other real-world scenes read its models";
  std::string scenes;
  for (const char* name : {"engine", "house", "teapots", "wuson"})
    scenes += (scenes.empty() ? "" : ",") + (kScenes / (std::string(name) + ".json")).string();
  const RunResult r = run("--scene " + scenes + " -N 4 -R 32 --width 24 --height 24 --no-reference");
  ASSERT_EQ(r.outcome.status, 0) << r.outcome.output;
  std::map<std::string, json> by_scene;
  for (const auto& record : r.records) {
    by_scene[record["scene_name"]] = record;
    EXPECT_EQ(record["status"], "ok") << record["config_id"] << ": " << record["status_detail"];
    EXPECT_EQ(record["degenerate"], "") << record["config_id"];
  }
  ASSERT_EQ(by_scene.size(), 4u);
  // From a closed character to an engine of overlapping parts: the depth profiles differ.
  EXPECT_GT(by_scene["engine"]["depth_p99"].get<int>(), 2 * by_scene["wuson"]["depth_p99"].get<int>());
  EXPECT_GT(by_scene["engine"]["triangles"].get<int>(), 100000);
}

TEST(Workloads, TheHairballIsEvenlyDeepTheSponzaLikeAtriumUneven) {
  const RunResult r = run("--scene " + (kScenes / "hairball.json").string() + "," + (kScenes / "sponza_like.json").string() +
                    " -N 4 -R 64 --width 24 --height 24 --no-reference");
  ASSERT_EQ(r.outcome.status, 0) << r.outcome.output;
  ASSERT_EQ(r.records.size(), 2u);
  std::map<std::string, json> by_scene;
  for (const auto& record : r.records) by_scene[record["scene_name"]] = record;
  const json& hair = by_scene["hairball"];
  const json& sponza = by_scene["sponza-like"];
  // Even: the hairball's median list is a large share of its deepest; uneven: the atrium's is not.
  const double hair_evenness = hair["depth_p50"].get<double>() / hair["max_depth_complexity"].get<double>();
  const double sponza_evenness = sponza["depth_p50"].get<double>() / sponza["max_depth_complexity"].get<double>();
  EXPECT_GT(hair_evenness, 2 * sponza_evenness) << hair["depth_histogram"] << " vs " << sponza["depth_histogram"];
  EXPECT_GT(hair["depth_p50"].get<int>(), sponza["depth_p50"].get<int>());
}

}  // namespace
}  // namespace ldm
