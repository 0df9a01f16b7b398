#pragma once
// The viewer's state and frame loop (harness/viewer/viewer.h says what it is): the
// configuration on screen and its MeasurementSession, the camera, the images, the
// reference rendering beside the frames, the point cloud, keys and the panel
// (viewer_panel.cpp). One object per window; GLFW's callbacks reach it (viewer.cpp).
#include <future>
#include <memory>
#include <string>

#include "harness/measuring/measurement_session.h"
#include "harness/settings/run_settings.h"
#include "harness/gl/bindings.h"
#include "harness/gl/egl_context.h"
#include "harness/gl/gl_objects.h"
#include "harness/metrics/image_metrics.h"
#include "harness/reference/reference_image.h"
#include "harness/viewer/camera_control.h"
#include "harness/viewer/display_image.h"
#include "harness/viewer/key_script.h"
#include "harness/viewer/point_cloud.h"
#include "harness/viewer/viewer.h"

struct GLFWwindow;

namespace ldm::viewer {

constexpr float kPanelWidth = 380.0f;
constexpr int kGap = 8;

class Viewer {
 public:
  Viewer(const ViewerOptions& options, GLFWwindow* window, DeviceInfo device)
      : options_(options),
        settings_(options.settings),
        window_(window),
        device_(std::move(device)),
        layout_(options.layout),
        show_panel_(options.show_panel),
        cloud_view_(options.cloud_view),
        script_(parse_key_script(options.script)) {
    display_program_ = build_program({{GL_VERTEX_SHADER, "viewer/display.vert", {}},
                                      {GL_FRAGMENT_SHADER, "viewer/display.frag", {}}},
                                     binding_defines());
    settings_.reference.progress = false;
  }

  int run();
  void on_key(int key, int mods);
  void on_mouse_button(int button, int action);
  void on_cursor(double x, double y);
  void on_scroll(double dy);

 private:
  void rebuild();
  void apply_camera();
  void run_frame();
  void update_reference();
  void request_reference();
  void draw_images(int fb_width, int fb_height);
  void draw_points(int x, int y, int w, int h, int fb_height);
  void draw_image(const DisplayImage& image, float x, float y, float scale, int fb_w, int fb_h);
  void draw_panel();
  void print_status() const;
  void save_screenshot(const std::string& path) const;
  void save_run(const std::string& path);
  int width() const { return settings_.width; }
  int height() const { return settings_.height; }

  ViewerOptions options_;
  RunSettings settings_;  // one value per axis: the configuration on screen
  GLFWwindow* window_;
  DeviceInfo device_;
  Layout layout_;
  bool show_panel_;
  uint32_t cloud_view_;
  bool colour_by_view_ = false;
  float point_size_ = 2.0f;
  uint32_t cloud_layers_ = 64;
  PointCloudCounts cloud_counts_;
  std::unique_ptr<PointCloud> cloud_;
  std::vector<KeyPress> script_;
  GlProgram display_program_;
  GlVertexArray empty_vao_;

  // The configuration and its session.
  bool config_dirty_ = true, camera_dirty_ = false;
  Configuration config_;
  std::string scene_spec_;
  std::unique_ptr<Scene> scene_;  // as loaded (world frame)
  std::unique_ptr<MeasurementSession> session_;
  std::string error_;
  bool have_measurement_ = false;
  Measurement measurement_;
  FrameTimes last_times_;
  int frame_ = 0;
  CameraControl camera_;

  DisplayImage pass_image_, reference_image_, error_image_;
  // The reference renders on the CPU beside the frames.
  std::future<ReferenceResult> reference_job_;
  std::string reference_job_key_, reference_key_;
  std::unique_ptr<ReferenceResult> reference_;
  std::string reference_status_ = "none (press G)";
  std::unique_ptr<ImageComparison> comparison_;
  bool reference_wanted_ = false;  // G: asked for once the configuration is built

  int screenshot_count_ = 0;
  std::string message_;
  std::string param_text_;
  bool param_text_loaded_ = false;
};


}  // namespace ldm::viewer
