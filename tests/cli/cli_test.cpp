// `ldmbench run` end to end: the main job writes records and images; bad input gets a clear
// error, a nonzero exit and no output folder; a failing configuration in a sweep is recorded
// as failed while the sweep goes on.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "support/test_support.h"

namespace ldm {
namespace {

namespace fs = std::filesystem;

using test::Outcome;

using test::ldmbench;
Outcome ldmbench_with_env(const std::string& environment, const std::string& args) {
  return ldmbench(args, environment);
}

using test::read_text;

TEST(Cli, MainJobWritesRecordsAndImages) {
  const fs::path out = fs::path(test::make_temp_dir("ldm-cli")) / "run";
  const std::string cache = test::make_temp_dir("ldm-cache");
  const Outcome o = ldmbench("run --scene cornell --structure psppsll --pass ao -N 4 -R 32 "
                             "--width 48 --height 40 --frames 2 --time-target 0 --warmup 1 --reference-spp 64 "
                             "--cache-dir " + cache + " --out " + out.string());
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
  // Accuracy against the reference, with the reference's own noise floor beside it.
  for (const char* key : {"mse", "nrmse", "psnr", "mssim", "ref_noise_mse", "ref_noise_mssim",
                          "ref_render_seconds", "mse_over_noise"})
    EXPECT_TRUE(r.contains(key) && r[key].is_number()) << key;
  EXPECT_EQ(r["ref_spp"], 128);  // 64 per half
  EXPECT_GT(r["mse"].get<double>(), 0.0);
  EXPECT_GT(r["mssim"].get<double>(), 0.0);
  EXPECT_LE(r["mssim"].get<double>(), 1.0);
  EXPECT_FALSE(r["ref_from_cache"].get<bool>());
  for (const char* key : {"reference_exr", "ssim_map_png", "diff_png"})
    EXPECT_TRUE(fs::is_regular_file(out / r[key].get<std::string>())) << key;
  // A second run takes the reference from the cache and measures the same error.
  const fs::path again = fs::path(test::make_temp_dir("ldm-cli")) / "again";
  ASSERT_EQ(ldmbench("run --scene cornell -N 4 -R 32 --width 48 --height 40 --frames 1 --time-target 0 "
                     "--warmup 0 --reference-spp 64 --cache-dir " + cache + " --out " +
                     again.string()).status, 0);
  const auto r2 = nlohmann::json::parse(read_text(again / "records.json"))["records"][0];
  EXPECT_TRUE(r2["ref_from_cache"].get<bool>());
  EXPECT_EQ(r2["ref_cache_key"], r["ref_cache_key"]);
  EXPECT_DOUBLE_EQ(r2["mse"].get<double>(), r["mse"].get<double>());
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
                             std::to_string(too_big) + ",16 --width 32 --height 32 --frames 1 --time-target 0 "
                             "--warmup 0 --no-reference --out " + out.string());
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
  const Outcome o = ldmbench("run --scene cornell -N 4 -R 32 --width 32 --height 32 --frames 1 --time-target 0 "
                             "--warmup 0 --param psppsll:capacity=1000 "
                             "--no-reference --out " + out.string());
  EXPECT_EQ(o.status, 0) << o.output;
  const auto r = nlohmann::json::parse(read_text(out / "records.json"))["records"][0];
  EXPECT_EQ(r["status"], "lossy");
  EXPECT_TRUE(r["overflow"].get<bool>());
  EXPECT_EQ(r["fragments_lost"].get<int64_t>(), r["fragments"].get<int64_t>() - 1000);
}

TEST(Cli, RecordsCarryTheSizingPolicyAndWhatItCost) {
  const fs::path out = fs::path(test::make_temp_dir("ldm-cli")) / "sizing";
  const Outcome o = ldmbench("run --scene atrium --structure psppsll,dfbuffer -N 4 -R 32 "
                             "--width 32 --height 32 --frames 2 --warmup 0 --time-target 0 --no-reference "
                             "--no-images --sizing oracle,census,previous_frame,budget "
                             "--sizing-budget-mib 1 --out " + out.string());
  ASSERT_EQ(o.status, 0) << o.output;
  const auto records = nlohmann::json::parse(read_text(out / "records.json"))["records"];
  ASSERT_EQ(records.size(), 8u);
  std::set<std::string> ids;
  for (const auto& r : records) {
    ids.insert(r["config_id"].get<std::string>());
    const std::string policy = r["sizing_policy"], structure = r["structure"];
    const std::string what = structure + " " + policy;
    EXPECT_EQ(r["status"], "ok") << what;
    EXPECT_TRUE(r.contains("sizing_rebuilds")) << what;
    // What each policy costs is in the timing columns, charged to the build.
    const bool census_pass = policy == "census" && structure == "psppsll";
    EXPECT_EQ(r.contains("census_ms_median"), census_pass) << what;
    EXPECT_EQ(r.contains("readback_ms_median"),
              policy == "previous_frame" || (policy == "census" && structure == "dfbuffer"))
        << what;
    if (policy == "oracle") EXPECT_NE(r["sizing_note"].get<std::string>().find("untimed"), std::string::npos);
    if (policy == "budget") EXPECT_LE(r["bytes_allocated"].get<double>(), double(1 << 20)) << what;
    if (policy == "previous_frame")  // the atrium has more fragments than LDM pixels
      EXPECT_EQ(r["sizing_rebuilds"].get<int64_t>(), 1) << what;
  }
  EXPECT_EQ(ids.size(), 8u) << "every policy is its own configuration";
}

// Issue 21: what a run costs beside its measured frames is in every record and at the end of
// the run: the build checks (sampled: one full check, the first build; --verify every: all
// of them), the baselines' frames, the measured frames' timed work.
TEST(Cli, RecordsSayWhatTheBuildChecksAndBaselinesCost) {
  const fs::path dir = fs::path(test::make_temp_dir("ldm-cli"));
  for (const std::string mode : {"sampled", "every"}) {
    const fs::path out = dir / mode;
    const Outcome o = ldmbench("run --scene cornell -N 4 -R 32 --width 32 --height 32 --frames 5 "
                               "--warmup 2 --time-target 0 --no-reference --no-images --verify " +
                               mode + " --out " + out.string());
    ASSERT_EQ(o.status, 0) << o.output;
    EXPECT_NE(o.output.find("harness cost: "), std::string::npos) << o.output;
    const auto r = nlohmann::json::parse(read_text(out / "records.json"))["records"][0];
    EXPECT_EQ(r["verify_mode"], mode);
    const int64_t full = r["verify_full_checks"], sampled = r["verify_sampled_checks"];
    EXPECT_EQ(full + sampled, 7) << "every build is checked, warm-up included";
    // Sampled: only the first build in full, as no build here lands on new storage.
    ASSERT_EQ(r["sizing_reallocations"].get<int64_t>(), 0);
    EXPECT_EQ(full, mode == "every" ? 7 : 1);
    EXPECT_EQ(r["baseline_frames"].get<int64_t>(), 3) << "measured frames 0, 2 and 4";
    const double timed = r["frames_timed_ms"], frame = r["frame_ms_median"];
    EXPECT_GE(timed, 5 * r["frame_ms_min"].get<double>());
    EXPECT_GT(timed, frame);
    EXPECT_NEAR(r["verify_share"].get<double>(), r["verify_ms"].get<double>() / timed, 1e-12);
  }
}

TEST(Cli, BadInputIsRejectedBeforeAnythingIsWritten) {
  const std::string dir = test::make_temp_dir("ldm-cli");
  const std::string missing = (fs::path(dir) / "nothere.json").string();
  test::expect_run_rejected("--scene " + missing, "nothere.json");
  std::ofstream(fs::path(dir) / "broken.json") << "{\n \"generator\": {\"type\": \"cornell\"\n";
  test::expect_run_rejected("--scene " + (fs::path(dir) / "broken.json").string(), "broken.json");
  test::expect_run_rejected("--scene cornell -N 0", "--views");
  test::expect_run_rejected("--scene cornell -R 0", "--r-ldm");
  test::expect_run_rejected("--scene cornell --width 5", "--width");
  test::expect_run_rejected("--scene cornell --frames 0", "--frames");
  test::expect_run_rejected("--scene cornell --d-max -1", "--d-max");
  test::expect_run_rejected("--scene cornell --structure linkedlist", "linkedlist");
  test::expect_run_rejected("--scene cornell --pass gi", "gi");
  test::expect_run_rejected("--scene cornell --param psppsll", "STRUCTURE:KEY=VALUE");
  test::expect_run_rejected("--scene cornell --param psppsll:pool=huge", "pool");
  test::expect_run_rejected("--scene cornell --sizing guess", "--sizing");
  test::expect_run_rejected("--scene cornell --sizing oracle,,census", "--sizing");
  test::expect_run_rejected("--scene cornell --sizing budget", "--sizing-budget-mib");
  test::expect_run_rejected("--scene cornell --sizing census --sizing-budget-mib 4", "--sizing-budget-mib");
  test::expect_run_rejected("--scene cornell --param psppsll:colour=red", "colour");
  test::expect_run_rejected("--scene cornell --visibility sometimes", "--visibility");
  test::expect_run_rejected("--scene nosuchscene", "nosuchscene");
  test::expect_run_rejected("--scene cornell --trace nearest", "--trace");
  test::expect_run_rejected("--scene cornell --ao-estimator mean", "--ao-estimator");
  // Every unknown name of a list at once, not only the first (issue 37).
  test::expect_run_rejected("--scene cornell --structure ppsll,foo,bar", "unknown structures 'foo', 'bar'");
}

// --gpu and LDM_GPU (issue 31): a bad value names its source, a GPU no device answers lists
// the devices, both exit 2 with nothing written; the option wins over the variable; `info`
// lists the EGL devices and says which it chose.
TEST(Cli, GpuChoiceIsCheckedAndListed) {
  const std::string run = "--scene cornell --structure ppfla -N 4 -R 32";
  test::expect_run_rejected(run + " --gpu x", "--gpu 'x': expected a GPU index");
  test::expect_run_rejected(run + " --gpu -1", "--gpu");
  test::expect_run_rejected(run + " --gpu 7", "--gpu 7: ");
  test::expect_run_rejected(run + " --gpu 7", "the EGL devices (`ldmbench info`):\n  0: ");
  const fs::path out = fs::path(test::make_temp_dir("ldm-cli")) / "out";
  Outcome o = ldmbench("run " + run + " --out " + out.string(), "LDM_GPU=two");
  EXPECT_EQ(o.status, 2) << o.output;
  EXPECT_NE(o.output.find("LDM_GPU='two'"), std::string::npos) << o.output;
  o = ldmbench("run " + run + " --out " + out.string(), "LDM_GPU=9");
  EXPECT_EQ(o.status, 2) << o.output;
  EXPECT_NE(o.output.find("LDM_GPU 9: "), std::string::npos) << o.output;
  EXPECT_FALSE(fs::exists(out));
  o = ldmbench("sweep " + std::string(LDM_TEST_SOURCE_DIR) + "/../sweeps/slurm-ci.json --gpu x --out " +
               out.string());
  EXPECT_EQ(o.status, 2) << o.output;
  EXPECT_NE(o.output.find("--gpu 'x'"), std::string::npos) << o.output;
  EXPECT_FALSE(fs::exists(out));
  o = ldmbench("info --gpu 0", "LDM_GPU=9");  // the option wins
  ASSERT_EQ(o.status, 0) << o.output;
  test::expect_contains(o.output, {"egl devices: ", "\n  0: ", "chosen: ", "(--gpu)", "gl driver: ", "device id: "});
  o = ldmbench("interleave a b --out x --gpu x -- run --scene cornell");
  EXPECT_EQ(o.status, 2) << o.output;
  EXPECT_NE(o.output.find("--gpu 'x'"), std::string::npos) << o.output;
#ifdef LDM_GBENCH_PATH
  o = test::run_shell(std::string(LDM_GBENCH_PATH) + " --ldm_scenes=cornell --ldm_structures=ppfla --ldm_gpu=9");
  EXPECT_EQ(o.status, 2) << o.output;
  EXPECT_NE(o.output.find("--ldm_gpu 9: "), std::string::npos) << o.output;
#endif
}

// The trace and the estimator are axes of the sweep and columns of the record; the reference
// depends on neither, so every configuration is scored against the same cached reference.
TEST(Cli, TraceAndEstimatorAreAxesScoredAgainstOneReference) {
  const fs::path out = fs::path(test::make_temp_dir("ldm-cli")) / "traces";
  const std::string cache = test::make_temp_dir("ldm-cache");
  const Outcome o = ldmbench("run --scene cornell -N 4 -R 32 --width 32 --height 32 --frames 1 --time-target 0 "
                             "--warmup 0 --reference-spp 16 --trace listing5,interval,plane "
                             "--ao-estimator eq13,normalized --cache-dir " + cache +
                             " --out " + out.string());
  ASSERT_EQ(o.status, 0) << o.output;
  const auto records = nlohmann::json::parse(read_text(out / "records.json"))["records"];
  ASSERT_EQ(records.size(), 6u);
  std::set<std::string> ids, combinations;
  for (const auto& r : records) {
    EXPECT_EQ(r["status"], "ok") << r["status_detail"];
    ids.insert(r["config_id"].get<std::string>());
    combinations.insert(r["trace"].get<std::string>() + "/" + r["ao_estimator"].get<std::string>());
    EXPECT_EQ(r["ref_cache_key"], records[0]["ref_cache_key"]);
    // The default offset (0.5 px) is too small for `interval`: measured, but said to be off.
    const bool warned =
        r["status_detail"].get<std::string>().find("trace interval") != std::string::npos;
    EXPECT_EQ(warned, r["trace"] == "interval") << r["status_detail"];
    ASSERT_TRUE(r["ao_max"].is_number() && r["ao_fraction_above_1"].is_number());
    // N = 4: Eq. 13's quadrature of the cosine overshoots 1 on the open parts of the box; the
    // normalised estimator never does.
    if (r["ao_estimator"] == "normalized") {
      EXPECT_LE(r["ao_max"].get<double>(), 1.0);
      EXPECT_EQ(r["ao_fraction_above_1"].get<double>(), 0.0);
    } else {
      EXPECT_GT(r["ao_max"].get<double>(), 1.0);
      EXPECT_GT(r["ao_fraction_above_1"].get<double>(), 0.0);
    }
  }
  EXPECT_EQ(ids.size(), 6u);
  EXPECT_EQ(combinations.size(), 6u);
  EXPECT_FALSE(records[0]["ref_from_cache"].get<bool>());
  EXPECT_TRUE(records[5]["ref_from_cache"].get<bool>());
}

TEST(Cli, ReferenceAndCompareImages) {
  const std::string dir = test::make_temp_dir("ldm-cli");
  const std::string ref = (fs::path(dir) / "ref.exr").string();
  const Outcome rendered = ldmbench("reference --scene cornell --width 32 --height 24 --spp 32 "
                                    "--no-cache --out " + ref);
  ASSERT_EQ(rendered.status, 0) << rendered.output;
  EXPECT_NE(rendered.output.find("spp: 64"), std::string::npos) << rendered.output;
  EXPECT_TRUE(fs::is_regular_file(fs::path(dir) / "ref.png"));
  // An image against itself: MSE 0, infinite PSNR, MSSIM exactly 1.
  const Outcome same = ldmbench("compare-images --json " + ref + " " + ref);
  ASSERT_EQ(same.status, 0) << same.output;
  const auto j = nlohmann::json::parse(same.output);
  EXPECT_EQ(j["mse"].get<double>(), 0.0);
  EXPECT_TRUE(j["psnr"].is_null());  // +infinity has no JSON number
  EXPECT_EQ(j["mssim"].get<double>(), 1.0);
  // Against an independent render with another seed: a small, positive error.
  const std::string other = (fs::path(dir) / "other.exr").string();
  ASSERT_EQ(ldmbench("reference --scene cornell --width 32 --height 24 --spp 32 --seed 9 "
                     "--no-cache --out " + other).status, 0);
  const auto k = nlohmann::json::parse(ldmbench("compare-images --json " + ref + " " + other).output);
  EXPECT_GT(k["mse"].get<double>(), 0.0);
  EXPECT_LT(k["mse"].get<double>(), 0.01);
  // Bad input: a missing file, mismatched sizes.
  const Outcome missing = ldmbench("compare-images " + ref + " " + dir + "/nothere.exr");
  EXPECT_EQ(missing.status, 2);
  EXPECT_NE(missing.output.find("nothere.exr"), std::string::npos);
  const std::string small = (fs::path(dir) / "small.exr").string();
  ASSERT_EQ(ldmbench("reference --scene cornell --width 16 --height 16 --spp 4 --no-cache --out " +
                     small).status, 0);
  const Outcome mismatch = ldmbench("compare-images " + ref + " " + small);
  EXPECT_EQ(mismatch.status, 2);
  EXPECT_NE(mismatch.output.find("32x24"), std::string::npos) << mismatch.output;
  const Outcome bad_out = ldmbench("reference --scene cornell --out " + dir + "/x.png");
  EXPECT_EQ(bad_out.status, 2);
}

#ifdef LDM_GBENCH_PATH
// ldmbench_gbench ARGS writing its JSON (--benchmark_out); a run that does not exit 0 fails
// the test and gives null.
nlohmann::json gbench_json(const std::string& args) {
  const std::string json = (fs::path(test::make_temp_dir("ldm-gbench")) / "out.json").string();
  const Outcome o = test::run_shell(std::string(LDM_GBENCH_PATH) + " " + args +
                                    " --benchmark_out_format=json --benchmark_out=" + json);
  EXPECT_EQ(o.status, 0) << o.output;
  return o.status == 0 ? nlohmann::json::parse(read_text(json)) : nlohmann::json();
}

// The Google Benchmark binary runs every structure and writes JSON that compare.py reads:
// one benchmark per configuration and pass (unique names), fixed iterations (the frames),
// every sub-pass a counter, repetitions aggregated the Google Benchmark way.
TEST(Gbench, OneBenchmarkPerConfigurationWithEverySubpassAsACounter) {
  const nlohmann::json j = gbench_json("--ldm_scenes=cornell --ldm_passes=all --ldm_views=4 --ldm_r_ldm=32 "
                                      "--ldm_image_size=32x32 --ldm_frames=3 --ldm_warmup=1 --benchmark_repetitions=2");
  ASSERT_FALSE(j.is_null());
  EXPECT_FALSE(j["context"]["gl_renderer"].get<std::string>().empty());
  EXPECT_FALSE(j["context"]["git_commit"].get<std::string>().empty());
  EXPECT_EQ(j["context"]["ldm_frames"], "3");
  // The context says what was measured (every axis), with which build, on which device.
  const auto& context = j["context"];
  EXPECT_EQ(context["ldm_views"], "4");
  EXPECT_EQ(context["ldm_image_size"], "32x32");
  EXPECT_EQ(context["ldm_passes"], "ao,indirect");
  EXPECT_EQ(context["ldm_structures"], "psppsll,ppsll,dfbuffer,habuffer,ppfla,psppfla");
  EXPECT_EQ(context["ldm_param"], "");
  for (const char* key : {"gl_vendor", "gl_version", "glsl_version", "egl_platform", "git_dirty",
                          "ldmbench_version", "ldmbench_build_type", "library_build_type_note"})
    EXPECT_FALSE(context.value(key, std::string()).empty()) << key << " missing from the context";
  std::set<std::string> names;
  size_t iterations = 0, aggregates = 0;
  for (const auto& b : j["benchmarks"]) {
    EXPECT_FALSE(b.contains("error_occurred") && b["error_occurred"].get<bool>()) << b["name"];
    if (b["run_type"] == "aggregate") {
      ++aggregates;
      continue;
    }
    ++iterations;
    EXPECT_EQ(b["iterations"].get<int>(), 3) << b["name"];
    EXPECT_GT(b["real_time"].get<double>(), 0.0) << b["name"];
    EXPECT_GT(b["fragments"].get<double>(), 0.0) << b["name"];
    for (const char* counter : {"build_ms", "pass_ms", "frame_ms", "gbuffer_ms"})
      EXPECT_GT(b.value(counter, 0.0), 0.0) << b["name"] << " " << counter;
    names.insert(b["run_name"].get<std::string>());
  }
  // Every structure under each structure pass (ao, indirect), each name once per pass.
  EXPECT_EQ(names.size(), 2 * 6u);
  EXPECT_EQ(iterations, 2 * names.size());  // two repetitions each
  EXPECT_GE(aggregates, 4 * names.size());  // mean, median, stddev, cv
  EXPECT_TRUE(names.count("ao/cornell/dfbuffer/N:4/R:32/iterations:3/manual_time"));
  EXPECT_TRUE(names.count("indirect/cornell/psppsll/N:4/R:32/iterations:3/manual_time"));
  EXPECT_EQ(test::run_shell(std::string(LDM_GBENCH_PATH) + " --ldm_views=0").status, 2);
  const Outcome help = test::run_shell(std::string(LDM_GBENCH_PATH) + " --help");
  EXPECT_NE(help.output.find("--ldm_frames"), std::string::npos) << help.output;
  // One line per --ldm_* flag, before Google Benchmark's own, with the version.
  for (const char* line : {"\n  --ldm_structures=LIST               structure psppsll|ppsll|dfbuffer|habuffer|ppfla|psppfla|all",
                           "\n  --ldm_views=LIST                    N [views] [1, 4096] (run's default 32)\n",
                           "\n  --ldm_param=OWNER:KEY=VALUE         a structure's or pass's parameter, repeatable\n"})
    EXPECT_NE(help.output.find(line), std::string::npos) << line << "\n" << help.output;
  EXPECT_LT(help.output.find("--ldm_param"), help.output.find("--benchmark_filter")) << help.output;
  EXPECT_EQ(help.output.rfind("ldmbench_gbench 0.", 0), 0u) << help.output;
}

// gbench judges builds as `ldmbench run` does (the same measure() and BuildHealth): a lossy
// configuration, which run records as "lossy" and measures, is timed with its loss counted,
// not refused; bad parameters are usage errors.
TEST(Gbench, LossyBuildsAreTimedLikeRunMeasuresThem) {
  const nlohmann::json j = gbench_json("--ldm_scenes=cornell --ldm_structures=ppfla --ldm_passes=ao --ldm_views=4 "
                                      "--ldm_r_ldm=32 --ldm_image_size=16x16 --ldm_param=ppfla:k=1 --ldm_frames=2");
  ASSERT_FALSE(j.is_null());
  ASSERT_EQ(j["benchmarks"].size(), 1u) << j.dump();
  const auto& b = j["benchmarks"][0];
  EXPECT_FALSE(b.contains("error_occurred") && b["error_occurred"].get<bool>()) << b.dump();
  EXPECT_GT(b["fragments_lost"].get<double>(), 0.0) << b.dump();
  EXPECT_GT(b["real_time"].get<double>(), 0.0);
  const Outcome bad = test::run_shell(std::string(LDM_GBENCH_PATH) + " --ldm_structures=ppfla --ldm_param=ppfla:kk=1");
  EXPECT_EQ(bad.status, 2) << bad.output;
  EXPECT_NE(bad.output.find("has no parameter 'kk'"), std::string::npos) << bad.output;
}
#endif

// A device without OpenGL 4.5 gets an error saying what it found. Mesa can be made to offer
// less than it supports; other drivers ignore the override, so there is nothing to test.
TEST(Cli, DeviceWithoutGl45IsRefusedWithWhatWasFound) {
  if (test::gl_context().device().gl_version.find("Mesa") == std::string::npos)
    GTEST_SKIP() << "MESA_GL_VERSION_OVERRIDE only applies to Mesa";
  const fs::path out = fs::path(test::make_temp_dir("ldm-cli")) / "old";
  const Outcome o = ldmbench_with_env("MESA_GL_VERSION_OVERRIDE=3.3",
                                      "run -N 2 -R 8 --no-reference --out " + out.string());
  EXPECT_EQ(o.status, 2) << o.output;
  EXPECT_NE(o.output.find("needs an OpenGL 4.5 core context"), std::string::npos) << o.output;
  EXPECT_NE(o.output.find("OpenGL 3.3"), std::string::npos) << o.output;
  EXPECT_FALSE(fs::exists(out));
}

TEST(Cli, HelpDocumentsEveryRunOption) {
  const Outcome o = ldmbench("run --help");
  EXPECT_EQ(o.status, 0);
  for (const char* option : {"--scene", "--structure", "--pass", "--views", "--r-ldm", "--width",
                             "--height", "--d-max", "--frames", "--warmup", "--out", "--param",
                             "--trace", "--ao-estimator"})
    EXPECT_NE(o.output.find(option), std::string::npos) << option;
}

}  // namespace
}  // namespace ldm
