// `ldmbench view`: the interactive viewer (harness/viewer/viewer.h) on one configuration of
// the run options.
#include <cstdio>
#include <iostream>
#include <memory>

#include "harness/run/run_command.h"
#include "harness/cli/commands.h"
#include "harness/cli/run_options.h"
#include "harness/scene/scene_loader.h"
#include "harness/util/error.h"
#include "harness/viewer/key_script.h"
#include "harness/viewer/viewer.h"

namespace ldm::cli {
namespace {

struct ViewOptions {
  RunOptions run;
  viewer::ViewerOptions viewer;
  std::string layout = "side";
  std::string window;  // WxH
};

// The viewer shows one configuration: every axis takes one value.
void require_single_values(const RunSettings& s) {
  auto one = [](const char* option, size_t count) {
    if (count > 1)
      throw UserError(std::string(option) + ": ldmbench view shows one configuration; give one "
                      "value (switch between them in the viewer), or sweep them with ldmbench run");
  };
  one("--scene", s.scenes.size());
  one("--structure", s.structures.size());
  one("--pass", s.passes.size());
  one("-N", s.views.size());
  one("-R", s.resolutions.size());
  one("--d-max", s.d_max.size());
  one("--visibility", s.visibility.size());
  one("--trace", s.traces.size());
  one("--ao-estimator", s.estimators.size());
  one("--sizing", s.sizing.size());
}

}  // namespace

Runner add_view_command(CLI::App& app, const std::string& program) {
  auto o = std::make_shared<ViewOptions>();
  o->viewer.program = program;
  auto* view = app.add_subcommand(
      "view", "Interactive viewer (needs a display; headless: xvfb-run -a ldmbench view ...): "
              "one configuration of the run options, changed live; keys in docs/guide/viewer.md");
  add_run_options(view, &o->run);
  // Here --frames counts the viewer's frames (the brief of --frames K --screenshot PATH);
  // the run's own --frames is --measured-frames.
  view->remove_option(view->get_option("--frames"));
  // The window's context is made by the display server (GLX, or EGL on X11), which picks
  // the GPU: --gpu chooses among headless EGL devices only (docs/guide/gpu-nodes.md).
  view->remove_option(view->get_option("--gpu"));
  o->run.gpu.option = nullptr;  // removed: never given
  viewer::ViewerOptions& v = o->viewer;
  view->add_option("--frames", v.frames, "Render this many frames, then exit (0: until closed)")
      ->check(CLI::Range(0, 1000000));
  view->add_option("--screenshot", v.screenshot, "With --frames: PNG of the window at the end");
  view->add_option("--save-run", v.save_run,
                   "Write the `ldmbench run` command line of the configuration shown at exit "
                   "(and on F5)");
  view->add_option("--script", v.script,
                   "Key presses FRAME:KEY,... injected through the key handler (e.g. 3:s,6:p)");
  view->add_flag("--print-status", v.print_status, "Print one status line per frame");
  view->add_option("--layout", o->layout, "side, pass, reference, error or points")
      ->check(CLI::IsMember({"side", "pass", "reference", "error", "points"}))
      ->capture_default_str();
  view->add_flag("!--hide-panel", v.show_panel, "Start without the ImGui panel (H toggles it)");
  view->add_option("--window", o->window, "Window size WxH (default: fitted)");
  view->add_option("--gl-api", v.gl_api, "Context API: auto (GLX, else EGL), glx, egl")
      ->check(CLI::IsMember({"auto", "glx", "egl"}))
      ->capture_default_str();
  view->add_option("--cloud-view", v.cloud_view, "LDM view of the point cloud (N: all views)");
  // `--frames` belongs to the viewer here; the record's frame count stays the run's default
  // unless --measured-frames says otherwise.
  view->add_option("--measured-frames", o->run.settings.frames,
                   "Frames per configuration that Save as run writes as --frames")
      ->check(CLI::Range(1, 100000));
  return [o]() {
    viewer::ViewerOptions options = o->viewer;
    options.settings = run_settings_from(&o->run);
    require_single_values(options.settings);
    // Bad input is refused before a window opens, as `run` refuses it before GPU work.
    validate_axes(options.settings);
    load_scene(options.settings.scenes.front());
    viewer::parse_key_script(options.script);
    options.layout = viewer::parse_layout(o->layout);
    if (!o->window.empty()) {
      int w = 0, h = 0;
      char rest = 0;
      if (std::sscanf(o->window.c_str(), "%dx%d%c", &w, &h, &rest) != 2 || w < 16 || h < 16 ||
          w > 16384 || h > 16384)
        throw UserError("--window: expected WxH (16..16384), got '" + o->window + "'");
      options.window_width = w;
      options.window_height = h;
    }
    return viewer::run_viewer(options);
  };
}

}  // namespace ldm::cli
