#pragma once
// `ldmbench view`: a GLFW window on the library code of `ldmbench run`. Each frame is a
// frame of MeasurementSession (harness/measuring/measurement_session.h), the loop measure() runs,
// and the figures on screen are its Measurement; the configuration is a RunSettings with one
// value per axis, turned into the measurement request exactly as `ldmbench run` does, so
// "Save as run" writes a command line that measures what is on screen.
//
// Only `ldmbench view` initialises GLFW and Dear ImGui (this folder is the library
// ldm_viewer; the rest of ldmbench never opens a window system).
#include <string>

#include "harness/settings/run_settings.h"

namespace ldm::viewer {

enum class Layout { SideBySide, Pass, Reference, Error, Points };

struct ViewerOptions {
  RunSettings settings;       // one value per axis
  std::string program = "ldmbench";  // how "Save as run" calls ldmbench
  int frames = 0;             // > 0: render this many frames, then exit
  std::string screenshot;     // PNG of the window after the last frame (with --frames)
  std::string save_run;       // write the `ldmbench run` command line here at exit
  std::string script;         // key presses "FRAME:KEY,..." injected through the key handler
  bool print_status = false;  // one status line per frame on stdout
  int window_width = 0, window_height = 0;  // 0: fitted to the images and the panel
  bool show_panel = true;
  Layout layout = Layout::SideBySide;
  std::string gl_api = "auto";  // auto (GLX, else EGL) | glx | egl
  uint32_t cloud_view = 0;      // the LDM of the point cloud (N: all views)
};

// Why no window can be opened here (no DISPLAY and no WAYLAND_DISPLAY), with what to do
// instead; empty when a display is named.
std::string missing_display_message();

Layout parse_layout(const std::string& name);  // side | pass | reference | error | points

// Runs the viewer until its window closes (or --frames are done); the exit status.
int run_viewer(const ViewerOptions& options);

}  // namespace ldm::viewer
