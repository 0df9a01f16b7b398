// `ldmbench view` as a person uses it, in a real window on a virtual X server (xvfb-run;
// Mesa llvmpipe through GLX): it starts and renders, keys typed into the window (xdotool)
// switch the structure and the pass, a screenshot of a configuration equals the image
// `ldmbench run` writes for the command line the viewer saves, and the point cloud holds
// every stored depth. Without a display it refuses with advice; `ldmbench run` needs none.
// Tests that need xvfb-run (or xdotool) skip, saying so, where it is not installed;
// scripts/setup.sh installs both, so CI runs them.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include <unistd.h>

#include "harness/settings/run_command_line.h"
#include "harness/image/image.h"
#include "harness/passes/pass.h"
#include "ldm_impls/ldm_structure.h"
#include "support/test_support.h"

namespace ldm {
namespace {

namespace fs = std::filesystem;

const std::string kLdm = LDM_BINARY_PATH;
// Tiny: 64 x 64 LDMs, 128 x 128 images, no reference.
const std::string kTiny = " --scene cornell -N 4 -R 64 --width 128 --height 128 --no-reference";
// The pass image alone, pixel for pixel, filling the window.
const std::string kImageOnly = " --layout pass --hide-panel --window 128x128";

bool installed(const std::string& tool) {
  std::string ignored;
  return test::run_command("command -v " + tool + " >/dev/null 2>&1", &ignored) == 0;
}

#define REQUIRE_TOOL(tool) \
  if (!installed(tool)) GTEST_SKIP() << tool << " is not installed (scripts/setup.sh installs it)"

// One status line of --print-status as key -> value.
using Status = std::map<std::string, std::string>;

std::vector<Status> status_lines(const std::string& output) {
  std::vector<Status> lines;
  std::istringstream in(output);
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind("frame=", 0) != 0) continue;
    Status s;
    std::istringstream words(line);
    std::string word;
    while (words >> word) {
      const auto eq = word.find('=');
      if (eq != std::string::npos) s[word.substr(0, eq)] = word.substr(eq + 1);
    }
    lines.push_back(s);
  }
  return lines;
}

// ctest -j runs tests side by side: each process starts its search for a free X display at
// its own number, so that two xvfb-run -a do not race for the same one.
std::string xvfb(const std::string& command) {
  const int first_display = 100 + int(getpid() % 800) * 4;
  return "xvfb-run -a -n " + std::to_string(first_display) + " -s '-screen 0 1280x1024x24' " +
         command + " 2>&1";
}

std::string next_after(const std::vector<std::string>& names, const std::string& name) {
  const auto it = std::find(names.begin(), names.end(), name);
  return names[size_t((it - names.begin() + 1) % names.size())];
}

// The 8-bit RGB colour of every pixel of a rectangle.
std::vector<std::array<int, 3>> colours(const Image& image, int x0, int y0, int w, int h) {
  const auto bytes = png_bytes(image);
  std::vector<std::array<int, 3>> out;
  for (int y = y0; y < y0 + h; ++y)
    for (int x = x0; x < x0 + w; ++x) {
      const size_t p = (size_t(y) * image.width + x) * image.channels;
      out.push_back({bytes[p], bytes[p + std::min(1, image.channels - 1)],
                     bytes[p + std::min(2, image.channels - 1)]});
    }
  return out;
}

// Share of the pixels that have the commonest colour: 1 for a blank image.
double commonest_colour_share(const std::vector<std::array<int, 3>>& pixels) {
  std::map<std::array<int, 3>, size_t> counts;
  size_t most = 0;
  for (const auto& c : pixels) most = std::max(most, ++counts[c]);
  return pixels.empty() ? 1.0 : double(most) / double(pixels.size());
}

double share_of_colour(const std::vector<std::array<int, 3>>& pixels, std::array<int, 3> colour) {
  return pixels.empty() ? 1.0
                        : double(std::count(pixels.begin(), pixels.end(), colour)) /
                              double(pixels.size());
}

TEST(Viewer, WithoutDisplaySaysSoAndExits2) {
  const std::string dir = test::make_temp_dir("ldm-view-headless");
  const std::string shot = dir + "/shot.png";
  std::string output;
  const int status = test::run_command("env -u DISPLAY -u WAYLAND_DISPLAY " + kLdm + " view" +
                                           kTiny + " --frames 1 --screenshot " + shot + " 2>&1",
                                       &output);
  EXPECT_EQ(status, 2) << output;
  for (const char* word : {"DISPLAY", "WAYLAND_DISPLAY", "xvfb-run -a ldmbench view"})
    EXPECT_NE(output.find(word), std::string::npos) << word << " not in: " << output;
  EXPECT_FALSE(fs::exists(shot));
}

TEST(Viewer, BadInputIsRefusedBeforeAnyWindow) {
  std::string output;
  EXPECT_EQ(test::run_command(kLdm + " view --structure nope --frames 1 2>&1", &output), 2);
  EXPECT_NE(output.find("unknown structure 'nope'"), std::string::npos) << output;
  EXPECT_EQ(test::run_command(kLdm + " view -N 4,8 --frames 1 2>&1", &output), 2);
  EXPECT_NE(output.find("one configuration"), std::string::npos) << output;
  EXPECT_EQ(test::run_command(kLdm + " view --script 2:nokey --frames 1 2>&1", &output), 2);
  EXPECT_NE(output.find("'2:nokey' is not FRAME:KEY"), std::string::npos) << output;
}

TEST(Viewer, RunNeedsNoDisplay) {
  const std::string dir = test::make_temp_dir("ldm-view-run");
  std::string output;
  const int status = test::run_command("env -u DISPLAY -u WAYLAND_DISPLAY " + kLdm + " run" +
                                           kTiny + " --frames 1 --warmup 0 --out " + dir +
                                           "/run 2>&1",
                                       &output);
  EXPECT_EQ(status, 0) << output;
  EXPECT_TRUE(fs::exists(dir + "/run/records.csv")) << output;
}

TEST(Viewer, StartsRendersFramesAndShowsTheMeasurement) {
  REQUIRE_TOOL("xvfb-run");
  const std::string shot = test::make_temp_dir("ldm-view-start") + "/window.png";
  std::string output;
  // The default window: the panel beside the pass image, reference and error map.
  const int status = test::run_command(
      xvfb(kLdm + " view" + kTiny + " --frames 3 --print-status --screenshot " + shot), &output);
  ASSERT_EQ(status, 0) << output;
  const auto lines = status_lines(output);
  ASSERT_EQ(lines.size(), 3u) << output;
  for (size_t i = 0; i < lines.size(); ++i) {
    EXPECT_EQ(lines[i].at("frame"), std::to_string(i));
    EXPECT_EQ(lines[i].at("status"), "ok") << output;
    EXPECT_EQ(lines[i].at("structure"), "psppsll");
    EXPECT_GT(std::stoull(lines[i].at("fragments")), 1000u);
    EXPECT_EQ(lines[i].at("stored"), lines[i].at("fragments"));
  }
  // After the two warm-up frames, the measured frame's times (Measurement::frames).
  EXPECT_GT(std::stod(lines[2].at("build_ms")), 0.0);
  const Image window = read_image(shot);
  ASSERT_GE(window.width, 380 + 128 * 3);  // the panel (380 px), then the images
  ASSERT_GE(window.height, 18 + 128);
  // The pass image, right of the panel below its label, is drawn: few of its pixels have the
  // window's background colour (its bottom-right corner) and it is not one colour.
  const auto background = colours(window, window.width - 1, window.height - 1, 1, 1).front();
  const auto pass_area = colours(window, 380, 18, 128, 128);
  EXPECT_LT(share_of_colour(pass_area, background), 0.2) << "no pass image drawn: " << shot;
  EXPECT_LT(commonest_colour_share(pass_area), 0.5) << "the pass image is blank: " << shot;
}

// Keys typed into the window through the X server (XTEST), as a person types them, and a
// mouse drag that orbits the camera.
TEST(Viewer, KeysAndDragInTheWindowSwitchStructurePassAndCamera) {
  REQUIRE_TOOL("xvfb-run");
  REQUIRE_TOOL("xdotool");
  const std::string dir = test::make_temp_dir("ldm-view-keys");
  const std::string script = dir + "/keys.sh";
  std::ofstream(script)
      << "timeout 60 " << kLdm << " view" << kTiny << kImageOnly << " --print-status > "
      << dir << "/status.txt 2>&1 &\n"
      << "pid=$!\n"
      << "wid=$(timeout 30 xdotool search --sync --onlyvisible --name 'ldmbench view' | head -1)\n"
      << "xdotool windowfocus --sync \"$wid\"\n"
      << "sleep 0.5; xdotool key s\n"
      << "sleep 0.5; xdotool key p\n"
      // An orbit: a drag across the window.
      << "sleep 0.5; xdotool mousemove --window \"$wid\" 40 64 mousedown 1\n"
      << "sleep 0.2; xdotool mousemove --window \"$wid\" 60 64\n"
      << "sleep 0.2; xdotool mousemove --window \"$wid\" 90 70 mouseup 1\n"
      << "sleep 0.5; xdotool key q\n"
      << "wait $pid\n";
  std::string output;
  ASSERT_EQ(test::run_command(xvfb("sh " + script), &output), 0) << output;
  std::ifstream in(dir + "/status.txt");
  std::stringstream text;
  text << in.rdbuf();
  const auto lines = status_lines(text.str());
  ASSERT_FALSE(lines.empty()) << text.str();
  const std::string structure = next_after(structure_names(), "psppsll");
  const std::string pass = next_after(pass_names(), "ao");
  // In order: the start, the next structure (S), then the next pass (P).
  size_t i = 0;
  auto advance_to = [&](const std::string& key, const std::string& value) {
    while (i < lines.size() && lines[i].at(key) != value) ++i;
    return i < lines.size();
  };
  EXPECT_EQ(lines.front().at("structure"), "psppsll");
  EXPECT_TRUE(advance_to("structure", structure)) << "S did not switch to " << structure << "\n"
                                                  << text.str();
  EXPECT_EQ(lines[std::min(i, lines.size() - 1)].at("pass"), "ao");
  EXPECT_TRUE(advance_to("pass", pass)) << "P did not switch to " << pass << "\n" << text.str();
  const std::string eye = lines[std::min(i, lines.size() - 1)].at("eye");
  EXPECT_NE(lines.back().at("eye"), eye) << "the drag did not orbit the camera\n" << text.str();
  EXPECT_EQ(lines.back().at("status"), "ok") << text.str();
}

// The same switches through --script, at known frames.
TEST(Viewer, ScriptedKeysSwitchAtTheirFrames) {
  REQUIRE_TOOL("xvfb-run");
  std::string output;
  const int status = test::run_command(
      xvfb(kLdm + " view" + kTiny + kImageOnly + " --frames 6 --print-status --script 2:s,4:p"),
      &output);
  ASSERT_EQ(status, 0) << output;
  const auto lines = status_lines(output);
  ASSERT_EQ(lines.size(), 6u) << output;
  const std::string structure = next_after(structure_names(), "psppsll");
  EXPECT_EQ(lines[1].at("structure"), "psppsll");
  EXPECT_EQ(lines[2].at("structure"), structure) << output;
  EXPECT_EQ(lines[3].at("pass"), "ao");
  EXPECT_EQ(lines[4].at("pass"), next_after(pass_names(), "ao")) << output;
}

// A configuration reached by keys, saved as a run command: `ldmbench run` measures the same
// configuration (config_id) and writes the PNG the viewer showed. Tolerance: every 8-bit
// value within 1 of the run's PNG and the mean difference below 0.01 levels (both are the
// same GPU computation converted by the same code; measured: identical).
TEST(Viewer, ScreenshotMatchesTheRunOfTheSavedCommand) {
  REQUIRE_TOOL("xvfb-run");
  const std::string dir = test::make_temp_dir("ldm-view-match");
  std::string output;
  const int status = test::run_command(
      xvfb(kLdm + " view" + kTiny + kImageOnly + " --frames 6 --script 1:s,2:t --print-status" +
           " --screenshot " + dir + "/view.png --save-run " + dir + "/run.sh"),
      &output);
  ASSERT_EQ(status, 0) << output;
  const auto lines = status_lines(output);
  ASSERT_FALSE(lines.empty()) << output;
  const std::string config = lines.back().at("config");
  EXPECT_EQ(lines.back().at("structure"), next_after(structure_names(), "psppsll"));
  EXPECT_EQ(lines.back().at("status"), "ok");

  std::ifstream saved(dir + "/run.sh");
  std::string command;
  std::getline(saved, command);
  ASSERT_NE(command.find(" run "), std::string::npos) << command;
  ASSERT_EQ(test::run_command("env -u DISPLAY " + command + " --out " + dir + "/run 2>&1", &output), 0)
      << command << "\n" << output;
  const std::string run_png = dir + "/run/images/" + config + "-ao.png";
  ASSERT_TRUE(fs::exists(run_png)) << "the saved command measured another configuration than "
                                   << config << ":\n" << output;

  const Image view = read_image(dir + "/view.png"), run = read_image(run_png);
  ASSERT_EQ(view.width, run.width);
  ASSERT_EQ(view.height, run.height);
  const auto view_bytes = png_bytes(view), run_bytes = png_bytes(run);
  double sum = 0;
  int worst = 0;
  for (int y = 0; y < run.height; ++y)
    for (int x = 0; x < run.width; ++x)
      for (int c = 0; c < 3; ++c) {
        const int a = view_bytes[(size_t(y) * view.width + x) * view.channels + c];
        const int b = run_bytes[(size_t(y) * run.width + x) * run.channels + std::min(c, run.channels - 1)];
        worst = std::max(worst, std::abs(a - b));
        sum += std::abs(a - b);
      }
  EXPECT_LE(worst, 1) << "the screenshot differs from " << run_png;
  EXPECT_LT(sum / double(run.pixel_count() * 3), 0.01);
  EXPECT_LT(commonest_colour_share(colours(run, 0, 0, run.width, run.height)), 0.5)
      << "the run's image is blank: no comparison";
}

// Each LDM's point cloud, stepped through with V: the depths read through the query API,
// summed over the views, are every fragment the structure stored; all views at once (the
// last step) the same; and the cloud is drawn.
TEST(Viewer, PointCloudHoldsEveryStoredDepth) {
  REQUIRE_TOOL("xvfb-run");
  const std::string shot = test::make_temp_dir("ldm-view-cloud") + "/cloud.png";
  std::string output;
  const int status = test::run_command(
      xvfb(kLdm + " view" + kTiny + " --layout points --hide-panel --window 128x128" +
           " --cloud-view 0 --frames 5 --script 1:v,2:v,3:v,4:v --print-status --screenshot " +
           shot),
      &output);
  ASSERT_EQ(status, 0) << output;
  const auto lines = status_lines(output);
  ASSERT_EQ(lines.size(), 5u) << output;
  uint64_t per_view_sum = 0;
  for (size_t v = 0; v < 4; ++v) {
    EXPECT_EQ(lines[v].at("cloud_view"), std::to_string(v));
    EXPECT_GT(std::stoull(lines[v].at("points_stored")), 0u) << "view " << v;
    EXPECT_EQ(lines[v].at("points_shown"), lines[v].at("points_stored"));
    per_view_sum += std::stoull(lines[v].at("points_stored"));
  }
  EXPECT_EQ(std::to_string(per_view_sum), lines[0].at("stored")) << output;
  EXPECT_EQ(lines[4].at("cloud_view"), "4") << "all views";
  EXPECT_EQ(lines[4].at("points_stored"), lines[4].at("stored"));
  const Image cloud = read_image(shot);
  EXPECT_LT(commonest_colour_share(colours(cloud, 0, 0, cloud.width, cloud.height)), 0.95)
      << "no points drawn: " << shot;
}

// The point cloud follows the structure as S steps through every one: its extraction program
// is compiled for each structure's query, also when the new structure happens to live at the
// address of the one before it (its program was once keyed by that address, and the
// psppfla after ppfla then showed no point at all, found by scripts/check-shaders.sh).
TEST(Viewer, PointCloudFollowsEveryStructure) {
  REQUIRE_TOOL("xvfb-run");
  const std::vector<std::string> names = structure_names();
  // Three rounds through every structure at tiny sizes, where the allocator reuses addresses
  // most (the old key failed about one round in two).
  const size_t frames = 3 * names.size();
  std::string script;
  for (size_t frame = 1; frame < frames; ++frame)
    script += (script.empty() ? "" : ",") + std::to_string(frame) + ":s";
  std::string output;
  const int status = test::run_command(
      xvfb(kLdm + " view --scene cornell -N 4 -R 8 --width 16 --height 16 --no-reference" +
           " --layout points --hide-panel --window 64x64 --cloud-view 4 --structure " +
           names.front() + " --frames " + std::to_string(frames) + " --script " + script +
           " --print-status"),
      &output);
  ASSERT_EQ(status, 0) << output;
  const auto lines = status_lines(output);
  ASSERT_EQ(lines.size(), frames) << output;
  for (size_t i = 0; i < frames; ++i) {
    const std::string& name = names[i % names.size()];
    EXPECT_EQ(lines[i].at("structure"), name) << output;
    EXPECT_GT(std::stoull(lines[i].at("stored")), 0u) << name;
    EXPECT_EQ(lines[i].at("points_stored"), lines[i].at("stored")) << name << " (frame " << i
                                                                   << "): all views";
  }
}

// What Save as run writes: every setting explicit, floats exact, words shell-quoted, and
// parameters of structures not measured left out (ldmbench run refuses them).
TEST(Viewer, SavedRunCommandLineIsExplicitAndQuoted) {
  RunSettings s;
  s.scenes = {"scenes/my scene.json"};
  s.structures = {"ppfla"};
  s.d_max = {0.1f};
  s.normal_offset_pixels = 0.7f;
  s.sizing = {SizingPolicy::Budget};
  s.sizing_budget_mib = 12.5;
  s.structure_params["ppfla"]["k"] = "4";
  s.structure_params["psppsll"]["capacity"] = "9";
  s.reference.enabled = false;
  const std::string line = run_command_line(s, "build/ldmbench", "out dir");
  // Every axis from its declaration (harness/settings/harness_axes.cpp), in canonical order, reals
  // as the shortest text that reads back as the same float.
  for (const char* part : {"build/ldmbench run --scene 'scenes/my scene.json' --pass ao --structure ppfla",
                           " --views 32 --r-ldm 128 ",
                           " --d-max 0.1 ", " --visibility scene ", " --normal-offset 0.7 ", " --trace plane ",
                           " --sizing budget --sizing-budget-mib 12.5 ", " --image-size 256x256 ",
                           " --frames 5 --warmup 2 --param ppfla:k=4 --repetitions 1 --isolation context --time-target 0.03 "
                           "--time-cap 2 --clock-warmup 3 --max-frames 1000 --timer auto --verify sampled --no-reference",
                           " --out 'out dir'"})
    EXPECT_NE(line.find(part), std::string::npos) << part << " not in: " << line;
  EXPECT_EQ(line.find("psppsll:capacity"), std::string::npos) << line;
  EXPECT_EQ(std::stof("0.1"), 0.1f);
  EXPECT_EQ(std::stof("0.7"), 0.7f);
  EXPECT_EQ(shell_quoted("it's"), "'it'\\''s'");
}

}  // namespace
}  // namespace ldm
