#include "harness/viewer/viewer.h"

// GLFW includes no GL header of its own: ldmbench's (libglvnd's core profile) comes first.
#include "harness/gl/gl_api.h"
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <imgui.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>

#include <cstdlib>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "harness/run/exit_codes.h"
#include "harness/gl/egl_context.h"
#include "harness/util/error.h"
#include "harness/viewer/key_script.h"
#include "harness/viewer/viewer_app.h"

namespace ldm::viewer {
namespace {

// GLFW calls back with the window; the viewer is its user pointer.
Viewer* viewer_of(GLFWwindow* window) {
  return static_cast<Viewer*>(glfwGetWindowUserPointer(window));
}

void install_callbacks(GLFWwindow* window) {
  glfwSetKeyCallback(window, [](GLFWwindow* w, int key, int, int action, int mods) {
    if (action != GLFW_PRESS && action != GLFW_REPEAT) return;
    if (ImGui::GetCurrentContext() && ImGui::GetIO().WantCaptureKeyboard) return;
    if (Viewer* v = viewer_of(w)) v->on_key(key, mods);
  });
  glfwSetMouseButtonCallback(window, [](GLFWwindow* w, int button, int action, int) {
    if (ImGui::GetCurrentContext() && ImGui::GetIO().WantCaptureMouse && action == GLFW_PRESS) return;
    if (Viewer* v = viewer_of(w)) v->on_mouse_button(button, action);
  });
  glfwSetCursorPosCallback(window, [](GLFWwindow* w, double x, double y) {
    if (Viewer* v = viewer_of(w)) v->on_cursor(x, y);
  });
  glfwSetScrollCallback(window, [](GLFWwindow* w, double, double dy) {
    if (ImGui::GetCurrentContext() && ImGui::GetIO().WantCaptureMouse) return;
    if (Viewer* v = viewer_of(w)) v->on_scroll(dy);
  });
}

// A window with an OpenGL 4.5 core context through GLX or EGL (GLFW's context creation
// APIs on X11). Returns null and says why when neither gives one.
GLFWwindow* open_window(const ViewerOptions& o, int width, int height, std::string& api_used) {
  std::vector<std::string> apis;
  if (o.gl_api == "auto") apis = {"glx", "egl"};
  else apis = {o.gl_api};
  for (const auto& api : apis) {
    glfwDefaultWindowHints();
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 5);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
    glfwWindowHint(GLFW_DEPTH_BITS, 24);
    glfwWindowHint(GLFW_RESIZABLE, GLFW_TRUE);
    glfwWindowHint(GLFW_CONTEXT_CREATION_API,
                   api == "egl" ? GLFW_EGL_CONTEXT_API : GLFW_NATIVE_CONTEXT_API);
    if (o.settings.context.debug_output) glfwWindowHint(GLFW_OPENGL_DEBUG_CONTEXT, GLFW_TRUE);
    if (GLFWwindow* window = glfwCreateWindow(width, height, "ldmbench view", nullptr, nullptr)) {
      api_used = api;
      return window;
    }
  }
  return nullptr;
}

}  // namespace

std::string missing_display_message() {
  const char* x11 = std::getenv("DISPLAY");
  const char* wayland = std::getenv("WAYLAND_DISPLAY");
  if ((x11 && *x11) || (wayland && *wayland)) return "";
  return "ldmbench view needs a display: neither DISPLAY nor WAYLAND_DISPLAY is set. On a "
         "headless machine run it under a virtual X server: xvfb-run -a ldmbench view ... "
         "(ldmbench run needs no display)";
}

Layout parse_layout(const std::string& name) {
  if (name == "side") return Layout::SideBySide;
  if (name == "pass") return Layout::Pass;
  if (name == "reference") return Layout::Reference;
  if (name == "error") return Layout::Error;
  if (name == "points") return Layout::Points;
  throw UserError("--layout: expected side, pass, reference, error or points, got '" + name + "'");
}

int run_viewer(const ViewerOptions& options) {
  const std::string no_display = missing_display_message();
  if (!no_display.empty()) {
    std::cerr << "ldmbench: error: " << no_display << "\n";
    return kExitUsage;
  }
  parse_key_script(options.script);  // bad input before any window
  glfwSetErrorCallback([](int code, const char* text) {
    std::cerr << "ldmbench view: GLFW error 0x" << std::hex << code << std::dec << ": " << text
              << "\n";
  });
  if (!glfwInit()) {
    std::cerr << "ldmbench: error: GLFW could not connect to the display (DISPLAY="
              << (std::getenv("DISPLAY") ? std::getenv("DISPLAY") : "") << "); try xvfb-run -a "
              << "ldmbench view ...\n";
    return kExitUsage;
  }
  const int w = options.settings.width, h = options.settings.height;
  int window_w = options.window_width, window_h = options.window_height;
  if (window_w <= 0)
    window_w = std::min(1920, (options.show_panel ? int(kPanelWidth) : 0) + 3 * w + 2 * kGap);
  if (window_h <= 0) window_h = std::min(1200, std::max(h + 18, options.show_panel ? 900 : 0));
  std::string api;
  GLFWwindow* window = open_window(options, window_w, window_h, api);
  if (!window) {
    glfwTerminate();
    std::cerr << "ldmbench: error: no window with an OpenGL 4.5 core context (" << options.gl_api
              << ")\n";
    return 1;
  }
  glfwMakeContextCurrent(window);
  glfwSwapInterval(0);  // frames as fast as they measure; a vsync wait is no sub-pass
  int status = 1;
  {
    std::unique_ptr<Viewer> viewer;
    try {
      const DeviceInfo device =
          describe_current_context("glfw-" + api, options.settings.context.debug_output);
      viewer = std::make_unique<Viewer>(options, window, device);
      glfwSetWindowUserPointer(window, viewer.get());
      install_callbacks(window);  // before ImGui's, which calls them after its own
      IMGUI_CHECKVERSION();
      ImGui::CreateContext();
      ImGui::GetIO().IniFilename = nullptr;  // no imgui.ini left in the working directory
      ImGui::StyleColorsDark();
      ImGui_ImplGlfw_InitForOpenGL(window, true);
      ImGui_ImplOpenGL3_Init("#version 450 core");
      status = viewer->run();
    } catch (const UserError& e) {
      std::cerr << "ldmbench: error: " << e.what() << "\n";
      status = kExitUsage;
    } catch (const std::exception& e) {
      std::cerr << "ldmbench view: failed: " << e.what() << "\n";
      status = 1;
    }
    if (ImGui::GetCurrentContext()) {
      ImGui_ImplOpenGL3_Shutdown();
      ImGui_ImplGlfw_Shutdown();
      ImGui::DestroyContext();
    }
    glfwSetWindowUserPointer(window, nullptr);
  }
  glfwDestroyWindow(window);
  glfwTerminate();
  return status;
}

}  // namespace ldm::viewer
