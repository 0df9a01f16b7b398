// The sweep file (harness/run/sweep_spec.h, sweep_plan.h): the product of the axes minus
// exclude filters plus include blocks, in a fixed order; strict checking with the file and
// JSON path in every message; combinations the same configuration collapsed; shards.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <set>

#include "harness/settings/run_command_line.h"
#include "harness/run/sweep_plan.h"
#include "harness/run/sweep_spec.h"
#include "harness/util/error.h"
#include "support/test_support.h"

namespace ldm {
namespace {

// The registry's axes (harness/settings/axis_registry.h) with fewer choices, so that the
// messages listing them stay short.
SweepVocabulary vocabulary() {
  SweepVocabulary v = current_sweep_vocabulary();
  auto restrict = [&v](const std::string& key, std::vector<std::string> names) {
    for (AxisSpec& a : v.axes)
      if (a.key == key) {
        a.dynamic_choices = nullptr;
        a.choices = std::move(names);
      }
  };
  restrict("structures", {"psppsll", "ppfla", "habuffer"});
  restrict("passes", {"ao", "hbao"});
  restrict("trace", {"listing5", "plane"});
  restrict("ao_estimator", {"eq13", "normalized"});
  std::map<std::string, std::vector<AxisSpec>> parameters;
  for (const char* owner : {"psppsll", "ppfla", "habuffer", "ao", "hbao"}) parameters[owner] = v.parameters[owner];
  v.parameters = parameters;
  return v;
}

std::vector<SweepAssignment> combinations(const std::string& text) {
  SweepSpec spec = parse_sweep_spec(text, "s.json", vocabulary());
  return sweep_combinations(spec);
}

// The message of the UserError that parsing `text` throws ("" when none).
std::string error_of(const std::string& text) {
  try {
    SweepSpec spec = parse_sweep_spec(text, "s.json", vocabulary());
    sweep_combinations(spec);
  } catch (const UserError& e) {
    return e.what();
  }
  return "";
}

TEST(SweepSpec, ProductMinusExcludeInAFixedOrder) {
  const auto c = combinations(R"({"axes": {"views": [4, 8], "structures": ["psppsll", "ppfla"],
                                  "r_ldm": 64},
                                  "exclude": [{"structures": "ppfla", "views": [8]}]})");
  // structures before views (canonical axis order), the last axis fastest; ppfla n8 removed.
  ASSERT_EQ(c.size(), 3u);
  EXPECT_EQ(c[0].at("structures"), "psppsll");
  EXPECT_EQ(c[0].at("views"), 4);
  EXPECT_EQ(c[1].at("views"), 8);
  EXPECT_EQ(c[2].at("structures"), "ppfla");
  EXPECT_EQ(c[2].at("views"), 4);
  EXPECT_EQ(c[2].at("r_ldm"), 64);
}

TEST(SweepSpec, IncludeBlocksReplaceAxesAndDuplicatesGo) {
  // Each include block is the main product with its axes replaced; the base point that two
  // blocks share is one combination.
  const auto c = combinations(R"({"axes": {"structures": "all", "views": 32, "d_max": 1.5},
                                  "include": [{"views": [16, 32]}, {"d_max": [0.5]}]})");
  // main: 3 structures x 1; block 1 adds n16 (n32 repeats); block 2 adds d0.5.
  EXPECT_EQ(c.size(), 3u + 3u + 3u);
  std::set<std::string> seen;
  for (const auto& a : c) EXPECT_TRUE(seen.insert(nlohmann::json(a).dump()).second);
  EXPECT_EQ(c[3].at("views"), 16);
  EXPECT_EQ(c[6].at("d_max"), 0.5);
}

TEST(SweepSpec, ExcludeAppliesToIncludedCombinationsAndWarnsWhenIdle) {
  SweepSpec spec = parse_sweep_spec(R"({"axes": {"structures": ["psppsll"], "views": 4},
                                         "include": [{"structures": ["ppfla"]}],
                                         "exclude": [{"structures": "ppfla"}, {"views": 4, "structures": "habuffer"}]})",
                                    "s.json", vocabulary());
  const auto c = sweep_combinations(spec);
  ASSERT_EQ(c.size(), 1u);
  EXPECT_EQ(c[0].at("structures"), "psppsll");
  ASSERT_EQ(spec.warnings.size(), 1u);
  EXPECT_NE(spec.warnings[0].find("exclude[1]"), std::string::npos) << spec.warnings[0];
}

TEST(SweepSpec, ErrorsNameTheFileAndTheJsonPath) {
  EXPECT_EQ(error_of(R"({"axes": {"structures": ["psppsll", "ppfla", "foo"]}})"),
            "s.json: axes.structures[2]: unknown structure \"foo\" (known: psppsll, ppfla, habuffer, or all)");
  EXPECT_EQ(error_of(R"({"axes": {"views": [4, "8"]}})"),
            "s.json: axes.views[1]: expected an integer (N), got a string");
  EXPECT_EQ(error_of(R"({"axes": {"views": [4, 5000]}})"),
            "s.json: axes.views[1]: N 5000 is out of range [1, 4096]");
  EXPECT_EQ(error_of(R"({"axes": {"views": [4, 4]}})"), "s.json: axes.views[1]: 4 appears twice");
  EXPECT_EQ(error_of(R"({"axes": {"views": []}})"), "s.json: axes.views: an axis needs at least one value");
  EXPECT_NE(error_of(R"({"axes": {"view": 4}})").find("s.json: axes.view: unknown axis \"view\""), std::string::npos);
  EXPECT_NE(error_of(R"({"axes": {}, "sweeps": 1})").find("s.json: sweeps: unknown key"), std::string::npos);
  EXPECT_EQ(error_of(R"({"description": "no axes"})"), "s.json: axes: missing (the object of axes to sweep)");
  EXPECT_NE(error_of(R"({"axes": {"d_max": 1e39}})").find("s.json: axes.d_max: d_max 1e+39 reads as inf"),
            std::string::npos);
  EXPECT_NE(error_of(R"({"axes": {"image_size": ["64x", "32x32"]}})").find("s.json: axes.image_size[0]: expected an image size"),
            std::string::npos);
  EXPECT_NE(error_of(R"({"axes": {"trace": "plane"}, "exclude": [{"views": 4}]})")
                .find("s.json: exclude[0].views: not an axis of this sweep"),
            std::string::npos);
  EXPECT_NE(error_of(R"({"axes": {"ppfla:k": "4,8"}})").find("s.json: axes.ppfla:k: a comma in a parameter value"),
            std::string::npos);
  EXPECT_NE(error_of(R"({"axes": {"foo:k": [1]}})").find("s.json: axes.foo:k: unknown structure or pass \"foo\""),
            std::string::npos);
  EXPECT_NE(error_of(R"({"axes": {"views": 4}, "settings": {"reference": {"sp": 4}}})")
                .find("s.json: settings.reference.sp: unknown key"),
            std::string::npos);
  EXPECT_NE(error_of(R"({"axes": {"views": 4}, "settings": {"images": "yes"}})")
                .find("s.json: settings.images: expected true or false"),
            std::string::npos);
  EXPECT_NE(error_of(R"({"axes": {"views": 4}, "settings": {"timing": {"clock_warmup_s": -1}}})")
                .find("s.json: settings.timing.clock_warmup_s: expected a number in [0, 600]"),
            std::string::npos)
      << error_of(R"({"axes": {"views": 4}, "settings": {"timing": {"clock_warmup_s": -1}}})");
  EXPECT_NE(error_of(R"({"axes": {"views": 4}, "include": [{}]})").find("s.json: include[0]: names no axis"),
            std::string::npos);
  // Syntax errors name their line and column (util/json_input.h), like scene files'.
  EXPECT_NE(error_of("{\"axes\": {\"views\": 4},}").find("s.json: malformed JSON at line 1, column 23"),
            std::string::npos)
      << error_of("{\"axes\": {\"views\": 4},}");
  EXPECT_NE(error_of("[1]").find("s.json: (top level): expected an object"), std::string::npos);
}

TEST(SweepSpec, CanonicalFormIgnoresLayout) {
  const SweepSpec a = parse_sweep_spec(R"({"axes": {"views": [4, 8], "r_ldm": 64}})", "a", vocabulary());
  const SweepSpec b = parse_sweep_spec("{ \"axes\" : {\n \"r_ldm\":64,\"views\":[4,8]} }", "b", vocabulary());
  const SweepSpec c = parse_sweep_spec(R"({"axes": {"views": [4, 16], "r_ldm": 64}})", "c", vocabulary());
  // Notes do not count either.
  const SweepSpec d = parse_sweep_spec(R"({"description": "x", "comment": ["y"],
      "axes": {"views": [4, 8], "r_ldm": 64, "comment": "z"}})", "d", vocabulary());
  EXPECT_EQ(a.canonical, b.canonical);
  EXPECT_EQ(a.canonical, d.canonical);
  EXPECT_NE(a.canonical, c.canonical);
}

TEST(SweepSpec, TooManyCombinationsIsAnErrorNotAnAllocation) {
  std::string values;
  for (int i = 1; i <= 400; ++i) values += (i > 1 ? "," : "") + std::to_string(i);
  EXPECT_NE(error_of(R"({"axes": {"views": [)" + values + R"(], "r_ldm": [)" + values + R"(], "frames": [1, 2]}})")
                .find("more than 100000 combinations"),
            std::string::npos);
}

TEST(SweepSpec, ShardIsIndexOverCount) {
  EXPECT_EQ(parse_shard("1/3").index, 1u);
  EXPECT_EQ(parse_shard("1/3").count, 3u);
  EXPECT_EQ(parse_shard("0/1").text(), "0/1");
  for (const char* bad : {"3/3", "1", "a/2", "-1/2", "0/0", "1/2/3", ""})
    EXPECT_THROW(parse_shard(bad), UserError) << bad;
}

std::string write_sweep_text(const std::string& dir, const std::string& text) {
  const std::string path = dir + "/sweep.json";
  std::ofstream(path) << text;
  return path;
}

TEST(SweepPlan, CombinationsAConfigurationDoesNotUseAreOne) {
  const std::string dir = test::make_temp_dir("ldm-sweep");
  // HBAO reads no structure, N or ppfla:k; psppsll reads no ppfla:k.
  const SweepPlan plan = plan_sweep(write_sweep_text(dir, R"({"axes": {
      "passes": ["ao", "hbao"], "structures": ["psppsll", "ppfla"], "views": [4, 8],
      "ppfla:k": [2, 4]}})"), RunSettings());
  EXPECT_EQ(plan.combinations, 16u);
  std::vector<std::string> ids;
  for (const auto& p : plan.configurations) ids.push_back(p.config.id());
  const std::vector<std::string> expected = {
      "cornell-psppsll-ao-n4-r128-plane-prevframe",     "cornell-psppsll-ao-n8-r128-plane-prevframe",
      "cornell-ppfla-ao-n4-r128-plane-k=2-prevframe",   "cornell-ppfla-ao-n4-r128-plane-k=4-prevframe",
      "cornell-ppfla-ao-n8-r128-plane-k=2-prevframe",   "cornell-ppfla-ao-n8-r128-plane-k=4-prevframe",
      "cornell-none-hbao"};
  EXPECT_EQ(ids, expected);
  EXPECT_EQ(plan.configurations[2].config.params.at("k"), "2");
  EXPECT_TRUE(plan.configurations[0].config.params.empty());
}

TEST(SweepPlan, VaryingImageSizeOrFramesNamesThemInTheId) {
  const std::string dir = test::make_temp_dir("ldm-sweep");
  const SweepPlan plan = plan_sweep(write_sweep_text(dir, R"({"axes": {"image_size": ["32x32", 48],
      "frames": 2}})"), RunSettings());
  ASSERT_EQ(plan.configurations.size(), 2u);
  EXPECT_EQ(plan.configurations[0].config.id(), "cornell-psppsll-ao-n32-r128-plane-prevframe-img32x32");
  EXPECT_EQ(plan.configurations[1].settings.width, 48);
  EXPECT_EQ(plan.configurations[1].settings.height, 48);
  EXPECT_EQ(plan.configurations[1].settings.frames, 2);
  // Held fixed, they are settings and the ids are those of `ldmbench run`.
  const SweepPlan fixed = plan_sweep(write_sweep_text(dir, R"({"axes": {"image_size": "32x24"}})"), RunSettings());
  EXPECT_EQ(fixed.configurations[0].config.id(), "cornell-psppsll-ao-n32-r128-plane-prevframe");
  EXPECT_EQ(fixed.configurations[0].settings.height, 24);
}

// What `ldmbench view` saves beside its command line: a sweep file that plans exactly the
// configurations and settings of those run settings (every setting away from its default).
TEST(SweepPlan, SweepFileOfRunSettingsPlansTheSameConfigurations) {
  RunSettings s;
  s.scenes = {"cornell"};
  s.structures = {"ppfla", "psppsll"};
  s.passes = {"ao"};
  s.views = {8, 16};
  s.resolutions = {48};
  s.d_max = {0.75f, 1.1f};
  s.traces = {AoTrace::Listing5};
  s.estimators = {AoEstimatorChoice::Normalized};
  s.sizing = {SizingPolicy::Census};
  s.sizing_initial_per_pixel = 3;
  s.structure_params["ppfla"]["k"] = "4";
  s.normal_offset_pixels = 1.25f;
  s.width = 40;
  s.height = 24;
  s.frames = 2;
  s.warmup = 1;
  s.timer = "fenced_wall_clock";
  s.write_images = false;
  s.reference.spp.spp_per_half = 8;
  s.reference.spp.target_noise_mse = 3e-5;
  s.reference.spp.max_spp_per_half = 64;
  s.reference.seed = 7;
  s.precision.cap_seconds = 1.5;
  s.precision.clock_warmup_seconds = 0.25;

  const std::string dir = test::make_temp_dir("ldm-sweep");
  const SweepPlan plan = plan_sweep(write_sweep_text(dir, sweep_file_json(s, "round trip")), RunSettings());
  std::vector<std::string> planned, expected;
  for (const auto& p : plan.configurations) planned.push_back(p.config.id());
  for (const auto& c : expand_configurations(s)) expected.push_back(c.id());
  EXPECT_EQ(planned, expected);
  ASSERT_FALSE(plan.configurations.empty());
  const RunSettings& got = plan.configurations.front().settings;
  EXPECT_EQ(got.width, 40);
  EXPECT_EQ(got.height, 24);
  EXPECT_EQ(got.frames, 2);
  EXPECT_EQ(got.warmup, 1);
  EXPECT_EQ(got.timer, "fenced_wall_clock");
  EXPECT_FALSE(got.write_images);
  EXPECT_EQ(got.sizing_initial_per_pixel, 3u);
  EXPECT_EQ(got.reference.spp.spp_per_half, 8u);
  EXPECT_EQ(got.reference.spp.target_noise_mse, 3e-5);
  EXPECT_EQ(got.reference.spp.max_spp_per_half, 64u);
  EXPECT_EQ(got.reference.seed, 7u);
  EXPECT_EQ(got.precision.cap_seconds, 1.5);
  EXPECT_EQ(got.precision.clock_warmup_seconds, 0.25);
  ASSERT_TRUE(got.normal_offset_pixels.has_value());
  EXPECT_EQ(*got.normal_offset_pixels, 1.25f);
}

TEST(SweepPlan, ValuesAreCheckedByTheirOwnersAtTheirPath) {
  const std::string dir = test::make_temp_dir("ldm-sweep");
  auto error = [&](const std::string& text) {
    try {
      plan_sweep(write_sweep_text(dir, text), RunSettings());
    } catch (const UserError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_NE(error(R"({"axes": {"structures": "habuffer", "habuffer:load_factor": [0.5, 100]}})")
                .find("sweep.json: axes.habuffer:load_factor[1]: "),
            std::string::npos);
  // An undeclared parameter is refused by the owner's declarations, naming the declared ones.
  EXPECT_NE(error(R"({"axes": {"structures": "ppfla", "ppfla:q": 1}})")
                .find("sweep.json: axes.ppfla:q: ppfla has no parameter \"q\" (its parameters: k)"),
            std::string::npos);
  EXPECT_NE(error(R"({"axes": {"scenes": ["cornell", "nope.json"]}})").find("sweep.json: axes.scenes[1]: "),
            std::string::npos);
  EXPECT_NE(error(R"({"axes": {"sizing": ["oracle", "budget"]}})")
                .find("sweep.json: combination {\"sizing\":\"budget\"}: the budget sizing policy needs"),
            std::string::npos);
  EXPECT_NE(error(R"({"axes": {"views": 4}, "exclude": [{"views": 4}]})").find("no configuration"),
            std::string::npos);
}

TEST(SweepPlan, SceneFilesAreFoundBesideTheSweepFile) {
  const std::string dir = test::make_temp_dir("ldm-sweep");
  std::filesystem::copy_file(std::string(LDM_TEST_SOURCE_DIR) + "/../scenes/cornell.json",
                             dir + "/box.json");
  const SweepPlan plan = plan_sweep(write_sweep_text(dir, R"({"axes": {"scenes": "box.json"}})"), RunSettings());
  ASSERT_EQ(plan.configurations.size(), 1u);
  EXPECT_EQ(plan.configurations[0].config.scene, dir + "/box.json");
}

}  // namespace
}  // namespace ldm
