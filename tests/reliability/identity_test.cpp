// What identifies a sweep, and what may not be given twice (issue 19, items 2 and 3): an
// edit of any field of a scene file (or of its mesh) makes a rerun into the same --out
// measure again or refuse, never resume the stale record (an edited ao.normal_offset was
// resumed); a value repeated in one option (-N 4,4) is refused, naming option and value.
#include <gtest/gtest.h>

#include "reliability_support.h"

namespace ldm::reliability {
namespace {

using test::Outcome;

const std::string kObj = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nf 1 2 3\nf 2 4 3\n"
                         "v 0 0 0.5\nv 1 0 0.5\nv 0 1 0.5\nf 5 6 7\n";

// Every field a scene file can set, with the mesh and materials it names.
const nlohmann::json kScene = nlohmann::json::parse(R"({
  "name": "edits",
  "generator": {"type": "cornell", "blocks": true},
  "meshes": [{"file": "quad.obj", "material": "white", "scale": 1.0, "translate": [2.5, 1, 2.5]}],
  "materials": {"white": [0.8, 0.8, 0.8], "red": [0.8, 0.1, 0.1]},
  "camera": {"eye": [2.78, 2.73, -6.5], "target": [2.78, 2.2, 2.8], "up": [0, 1, 0], "fov_y_deg": 42},
  "light": {"type": "spot", "position": [2.78, 5.4, 2.8], "direction": [0, -1, 0], "intensity": 5,
            "inner_angle_deg": 20, "outer_angle_deg": 40},
  "ao": {"attenuated": true, "d_max": 1.5, "falloff_exponent": 2, "normal_offset": 0.5}
})");

TEST(ReliabilityIdentity, EditingAnyFieldOfASceneFileIsAnotherSweep) {
  const fs::path dir = test::make_temp_dir("ldm-identity");
  const std::string scene = (dir / "edits.json").string();
  write_file(dir / "quad.obj", kObj);
  write_file(scene, kScene.dump(2));
  const fs::path base = dir / "base";
  const std::string args = "run --scene " + scene + " -N 2" + kTiny + "--out ";
  ASSERT_EQ(test::ldmbench(args + base.string()).status, 0);

  const std::vector<std::pair<std::string, nlohmann::json>> edits = {
      {"/name", "edits2"},
      {"/generator/blocks", false},
      {"/meshes/0/material", "red"},
      {"/meshes/0/scale", 1.5},
      {"/meshes/0/translate", {2.5, 1, 2.75}},
      {"/materials/white", {0.5, 0.8, 0.8}},
      {"/camera/eye", {2.78, 2.8, -6.5}},
      {"/camera/target", {2.78, 2.3, 2.8}},
      {"/camera/up", {0.1, 1, 0}},
      {"/camera/fov_y_deg", 45},
      {"/light/position", {2.78, 5.3, 2.8}},
      {"/light/direction", {0, -1, 0.1}},
      {"/light/intensity", 6},
      {"/light/inner_angle_deg", 25},
      {"/light/outer_angle_deg", 45},
      {"/ao/attenuated", false},
      {"/ao/d_max", 1.25},
      {"/ao/falloff_exponent", 3},
      {"/ao/normal_offset", 0.75},  // the issue's case: resumed as it was
  };
  auto expect_not_resumed = [&](const std::string& what) {
    const fs::path out = dir / ("rerun-" + std::to_string(std::hash<std::string>{}(what)));
    fs::copy(base, out, fs::copy_options::recursive);
    const Outcome o = test::ldmbench(args + out.string());
    // Refused as another sweep (exit 2), or measured again: never the old record kept.
    const bool refused = o.status == 2 && o.output.find("different sweep") != std::string::npos;
    const bool measured = o.status == 0 && journal_entries(out, "record").size() == 2;
    EXPECT_TRUE(refused || measured) << what << ": exit " << o.status << "\n" << o.output;
  };
  for (const auto& [pointer, value] : edits) {
    nlohmann::json edited = kScene;
    edited[nlohmann::json::json_pointer(pointer)] = value;
    write_file(scene, edited.dump(2));
    expect_not_resumed(pointer);
  }
  // The mesh's bytes count too (one vertex moved).
  write_file(scene, kScene.dump(2));
  write_file(dir / "quad.obj", kObj + "v 0 0 0.75\n");
  expect_not_resumed("quad.obj");
  write_file(dir / "quad.obj", kObj);
  // Unedited, or only reformatted (the identity is the canonical JSON: tests/axes
  // identity_test.cpp), the same command resumes (the identity is not random).
  write_file(scene, kScene.dump(4));
  const Outcome same = test::ldmbench(args + base.string());
  EXPECT_EQ(same.status, 0) << same.output;
  EXPECT_NE(same.output.find("resuming: 1"), std::string::npos) << same.output;
}

TEST(ReliabilityIdentity, AValueGivenTwiceIsRefusedNamingOptionAndValue) {
  const fs::path dir = test::make_temp_dir("ldm-identity");
  // (arguments, the option the refusal names, what it says)
  std::vector<std::tuple<std::string, std::string, std::string>> cases = {
      {"-N 4,4", "--views", "4 appears twice"},
      {"-N 2 -R 8,16,8", "--r-ldm", "8 appears twice"},
      {"-N 2 --structure psppsll --structure psppsll", "--structure", "psppsll appears twice"},
      {"-N 2 --structure psppsll,ppfla,psppsll", "--structure", "psppsll appears twice"},
      {"-N 2 --d-max 1,1.0", "--d-max", "1 appears twice"},
      {"-N 2 --structure ppfla --param ppfla:k=4,4", "--param ppfla:k=4,4", "4 appears twice"},
      {"-N 2 --structure ppfla --param ppfla:k=4 --param ppfla:k=8", "--param ppfla:k", "given twice (4 and 8)"},
  };
  // And one value twice in an option's comma list ("--pass ao,ao").
  for (const auto& [option, value] : std::vector<std::pair<std::string, std::string>>{
           {"--scene", "cornell"}, {"--pass", "ao"}, {"--trace", "plane"}, {"--sizing", "census"},
           {"--visibility", "attenuated"}})
    cases.emplace_back("-N 2 " + option + " " + value + "," + value, option, value + " appears twice");
  for (const auto& [args, option, what] : cases) {
    const fs::path out = dir / "out";
    const Outcome o = test::ldmbench("run " + args + kTiny + "--out " + out.string());
    EXPECT_EQ(o.status, 2) << args << "\n" << o.output;
    EXPECT_NE(o.output.find(option), std::string::npos) << args << "\n" << o.output;
    EXPECT_NE(o.output.find(what), std::string::npos) << args << "\n" << o.output;
    EXPECT_FALSE(fs::exists(out)) << args;
    // --dry-run lists nothing twice either: it is refused the same way.
    EXPECT_EQ(test::ldmbench("run " + args + kTiny + "--dry-run").status, 2) << args;
  }
}

}  // namespace
}  // namespace ldm::reliability
