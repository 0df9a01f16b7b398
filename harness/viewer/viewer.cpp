#include "harness/viewer/viewer.h"

// GLFW includes no GL header of its own: ldmbench's (libglvnd's core profile) comes first.
#include "harness/gl/gl_api.h"
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <imgui.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <future>
#include <iostream>
#include <memory>
#include <sstream>

#include <glm/gtc/matrix_transform.hpp>

#include "harness/app/ldm_setup.h"
#include "harness/app/measure_configuration.h"
#include "harness/app/measurement_session.h"
#include "harness/app/run_command.h"
#include "harness/app/run_command_line.h"
#include "harness/gl/bindings.h"
#include "harness/gl/egl_context.h"
#include "harness/gl/gl_objects.h"
#include "harness/image/image.h"
#include "harness/metrics/heat_map.h"
#include "harness/metrics/image_metrics.h"
#include "harness/reference/reference_settings.h"
#include "harness/scene/camera.h"
#include "harness/scene/generators.h"
#include "harness/scene/scene_loader.h"
#include "harness/util/error.h"
#include "harness/viewer/camera_control.h"
#include "harness/viewer/key_script.h"
#include "harness/viewer/point_cloud.h"

namespace ldm::viewer {
namespace {

constexpr float kPanelWidth = 380.0f;
constexpr int kGap = 8;

// An 8-bit RGBA texture shown pixel for pixel (shaders/viewer/display.*).
struct DisplayImage {
  GlTexture2D texture;
  int width = 0, height = 0;
  bool valid = false;

  // `bytes`: png_bytes() of an image with `channels` channels, rows top first.
  void upload(const std::vector<unsigned char>& bytes, int w, int h, int channels) {
    std::vector<unsigned char> rgba(size_t(w) * h * 4, 255);
    for (size_t p = 0; p < size_t(w) * h; ++p)
      for (int c = 0; c < 3; ++c) rgba[p * 4 + c] = bytes[p * channels + std::min(c, channels - 1)];
    if (!valid || w != width || h != height) {
      texture = GlTexture2D(GL_RGBA8, w, h);
      glTextureParameteri(texture.id(), GL_TEXTURE_MIN_FILTER, GL_NEAREST);
      glTextureParameteri(texture.id(), GL_TEXTURE_MAG_FILTER, GL_NEAREST);
      glTextureParameteri(texture.id(), GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
      glTextureParameteri(texture.id(), GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
      width = w;
      height = h;
    }
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glTextureSubImage2D(texture.id(), 0, 0, 0, w, h, GL_RGBA, GL_UNSIGNED_BYTE, rgba.data());
    valid = true;
  }
};

// What a reference was rendered for: it is shown only while the view is the same.
std::string reference_key(const Configuration& config, const Camera& camera, int w, int h) {
  std::ostringstream key;
  key.precision(9);
  key << config.id() << " " << w << "x" << h << " " << camera.eye.x << "," << camera.eye.y
      << "," << camera.eye.z << " " << camera.target.x << "," << camera.target.y << ","
      << camera.target.z << " " << camera.up.x << "," << camera.up.y << "," << camera.up.z
      << " " << camera.fov_y_deg;
  return key.str();
}

template <typename T>
T cycled(const std::vector<T>& values, const T& current, int step) {
  if (values.empty()) return current;
  auto it = std::find(values.begin(), values.end(), current);
  const int n = int(values.size());
  const int at = it == values.end() ? 0 : int(it - values.begin());
  return values[size_t(((at + step) % n + n) % n)];
}

std::string format_ms(double ms) {
  char b[32];
  std::snprintf(b, sizeof b, "%.4g", ms);
  return b;
}

std::string format_bytes(uint64_t bytes) {
  char b[32];
  if (bytes >= (1u << 20))
    std::snprintf(b, sizeof b, "%.2f MiB", double(bytes) / double(1u << 20));
  else
    std::snprintf(b, sizeof b, "%.1f KiB", double(bytes) / 1024.0);
  return b;
}

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
  const std::string& current(const std::vector<std::string>& axis) const { return axis.front(); }
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

void Viewer::rebuild() {
  config_dirty_ = false;
  session_.reset();
  have_measurement_ = false;
  error_.clear();
  try {
    const std::vector<Configuration> configs = expand_configurations(settings_);
    if (configs.size() != 1)
      throw UserError("the viewer shows one configuration, these settings give " +
                      std::to_string(configs.size()));
    config_ = configs.front();
    if (!scene_ || scene_spec_ != config_.scene) {
      scene_ = std::make_unique<Scene>(load_scene(config_.scene));
      scene_spec_ = config_.scene;
      camera_.reset(scene_->camera, scene_->bounding_sphere());
    }
    session_ = std::make_unique<MeasurementSession>(
        *scene_, measurement_request(config_, settings_, device_));
    apply_camera();
  } catch (const std::exception& e) {
    session_.reset();
    error_ = e.what();
  }
}

// The session computes in its scene's frame (centred for LDM passes).
void Viewer::apply_camera() {
  camera_dirty_ = false;
  if (!session_) return;
  Camera camera = camera_.camera();
  camera.eye -= session_->scene().frame_origin;
  camera.target -= session_->scene().frame_origin;
  const Camera& now = session_->scene().camera;
  if (camera.eye == now.eye && camera.target == now.target && camera.up == now.up &&
      camera.fov_y_deg == now.fov_y_deg)
    return;
  session_->set_camera(camera);
}

void Viewer::run_frame() {
  if (config_dirty_) rebuild();
  if (camera_dirty_) {
    try {
      apply_camera();
    } catch (const std::exception& e) {
      session_.reset();
      error_ = e.what();
    }
  }
  if (!session_) return;
  try {
    last_times_ = session_->run_frame();
    measurement_ = session_->result();
    have_measurement_ = true;
    const Image& image = measurement_.images.front().image;
    pass_image_.upload(png_bytes(image), image.width, image.height, image.channels);
    if (layout_ == Layout::Points && session_->structure()) {
      if (!cloud_) cloud_ = std::make_unique<PointCloud>();
      const uint32_t views = session_->setup()->views.size();
      cloud_view_ = std::min(cloud_view_, views);
      cloud_counts_ = cloud_->extract(*session_->structure(), *session_->setup()->gpu_views,
                                      cloud_view_, cloud_layers_);
    }
  } catch (const std::exception& e) {
    session_.reset();
    have_measurement_ = false;
    error_ = e.what();
  }
}

void Viewer::request_reference() {
  if (!session_ || !scene_) return;
  const std::string key = reference_key(config_, camera_.camera(), width(), height());
  if (reference_job_.valid()) {
    message_ = "a reference is still rendering";
    return;
  }
  Scene scene = *scene_;
  scene.camera = camera_.camera();
  const Configuration config = config_;
  const ReferenceSettings settings = settings_.reference;
  const int w = width(), h = height();
  reference_job_key_ = key;
  reference_status_ = "rendering on the CPU...";
  reference_job_ = std::async(std::launch::async, [scene, config, settings, w, h]() {
    const auto pass =
        make_pass(config.pass, StructureParams(config.pass_params, "--pass " + config.pass));
    return pass->reference(scene, w, h, settings);
  });
}

void Viewer::update_reference() {
  if (reference_job_.valid() &&
      reference_job_.wait_for(std::chrono::seconds(0)) == std::future_status::ready) {
    try {
      reference_ = std::make_unique<ReferenceResult>(reference_job_.get());
      reference_key_ = reference_job_key_;
      reference_image_.upload(png_bytes(reference_->image), reference_->image.width,
                              reference_->image.height, reference_->image.channels);
    } catch (const std::exception& e) {
      reference_.reset();
      reference_status_ = std::string("failed: ") + e.what();
    }
  }
  comparison_.reset();
  error_image_.valid = false;
  const bool current = reference_ && have_measurement_ &&
                       reference_key_ == reference_key(config_, camera_.camera(), width(), height());
  if (!reference_) return;
  if (!current) {
    reference_status_ = "stale: the view changed (press G)";
    return;
  }
  char text[160];
  std::snprintf(text, sizeof text, "%u spp%s, noise MSE %.3g", reference_->spp_total,
                reference_->from_cache ? " (cache)" : "", reference_->noise_mse);
  reference_status_ = text;
  try {
    comparison_ = std::make_unique<ImageComparison>(
        compare_images(reference_->image, measurement_.images.front().image, {}));
    const Image& diff = comparison_->abs_diff;
    const float max_diff = *std::max_element(diff.pixels.begin(), diff.pixels.end());
    const Image heat = heat_map(diff, max_diff > 0 ? max_diff : 1.0);
    error_image_.upload(png_bytes(heat), heat.width, heat.height, heat.channels);
  } catch (const std::exception& e) {
    reference_status_ = std::string("not compared: ") + e.what();
  }
}

void Viewer::draw_image(const DisplayImage& image, float x, float y, float scale, int fb_w,
                        int fb_h) {
  if (!image.valid) return;
  const float x0 = 2.0f * x / float(fb_w) - 1.0f;
  const float x1 = 2.0f * (x + image.width * scale) / float(fb_w) - 1.0f;
  const float y_top = 1.0f - 2.0f * y / float(fb_h);
  const float y_bottom = 1.0f - 2.0f * (y + image.height * scale) / float(fb_h);
  display_program_.use();
  glProgramUniform4f(display_program_.id(), display_program_.uniform("rect"), x0, y_bottom, x1,
                     y_top);
  glBindTextureUnit(0, image.texture.id());
  glBindVertexArray(empty_vao_.id());
  glDrawArrays(GL_TRIANGLE_STRIP, 0, 4);
  glBindVertexArray(0);
}

void Viewer::draw_points(int x, int y, int w, int h, int fb_height) {
  if (!cloud_ || !session_ || !session_->structure() || w <= 0 || h <= 0) return;
  glViewport(x, fb_height - y - h, w, h);
  glEnable(GL_SCISSOR_TEST);
  glScissor(x, fb_height - y - h, w, h);
  glClearColor(0.05f, 0.05f, 0.07f, 1.0f);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  glDisable(GL_SCISSOR_TEST);
  Camera camera = camera_.camera();
  camera.eye -= session_->scene().frame_origin;
  camera.target -= session_->scene().frame_origin;
  const glm::mat4 vp =
      camera_view_projection(camera, w, h, session_->scene().bounding_sphere());
  cloud_->draw(vp, colour_by_view_, point_size_);
}

void Viewer::draw_images(int fb_width, int fb_height) {
  const int left = show_panel_ ? int(kPanelWidth) : 0;
  const int avail_w = fb_width - left, avail_h = fb_height;
  glViewport(0, 0, fb_width, fb_height);
  if (layout_ == Layout::Points) {
    draw_points(left, 0, avail_w, avail_h, fb_height);
    glViewport(0, 0, fb_width, fb_height);
    return;
  }
  std::vector<std::pair<const DisplayImage*, const char*>> shown;
  if (layout_ == Layout::SideBySide)
    shown = {{&pass_image_, "pass"}, {&reference_image_, "reference"}, {&error_image_, "|error|"}};
  else if (layout_ == Layout::Pass)
    shown = {{&pass_image_, "pass"}};
  else if (layout_ == Layout::Reference)
    shown = {{&reference_image_, "reference"}};
  else
    shown = {{&error_image_, "|error|"}};
  const bool labels = layout_ == Layout::SideBySide;
  const int label_h = labels ? 18 : 0;
  const float total_w = float(shown.size()) * width() + float(shown.size() - 1) * kGap;
  // Pixel for pixel when it fits (so a screenshot is the pass's image), else scaled down;
  // small images are enlarged by whole factors.
  float scale = std::min(float(avail_w) / total_w, float(avail_h - label_h) / float(height()));
  scale = scale >= 1.0f ? std::floor(scale) : scale;
  float x = float(left);
  for (const auto& [image, label] : shown) {
    const bool current = image == &pass_image_ || (image->valid && comparison_);
    if (current) draw_image(*image, x, float(label_h), scale, fb_width, fb_height);
    if (labels)
      ImGui::GetForegroundDrawList()->AddText(ImVec2(x + 2, 2), IM_COL32(230, 230, 230, 255),
                                              label);
    x += width() * scale + kGap;
  }
}

void Viewer::print_status() const {
  std::ostringstream line;
  const Camera& camera = camera_.camera();
  line << "frame=" << frame_ << " config=" << config_.id() << " scene=" << config_.scene << " structure=" << config_.structure
       << " pass=" << config_.pass << " N=" << config_.views << " R=" << config_.resolution
       << " trace=" << ao_trace_name(config_.trace)
       << " sizing=" << sizing_policy_name(config_.sizing.policy);
  if (have_measurement_) {
    const Measurement& m = measurement_;
    line << " status=" << build_status_name(m.status) << " fragments=" << m.census.fragments
         << " stored=" << m.last_build.fragments_stored << " lost=" << m.last_build.fragments_lost
         << " bytes_allocated=" << m.bytes_allocated();
    for (const auto& [name, ms] : last_times_)
      if (name == "build" || name == "frame") line << " " << name << "_ms=" << format_ms(ms);
  } else {
    line << " status=error error=\"" << error_ << "\"";
  }
  char eye[96];
  std::snprintf(eye, sizeof eye, " eye=%.4g,%.4g,%.4g", camera.eye.x, camera.eye.y, camera.eye.z);
  line << eye;
  if (layout_ == Layout::Points)
    line << " cloud_view=" << cloud_view_ << " points_stored=" << cloud_counts_.stored
         << " points_shown=" << cloud_counts_.shown;
  std::cout << line.str() << std::endl;
}

void Viewer::save_screenshot(const std::string& path) const {
  int w = 0, h = 0;
  glfwGetFramebufferSize(window_, &w, &h);
  std::vector<unsigned char> rows(size_t(w) * h * 3);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadBuffer(GL_BACK);
  glReadPixels(0, 0, w, h, GL_RGB, GL_UNSIGNED_BYTE, rows.data());
  std::vector<unsigned char> top_first(rows.size());
  for (int y = 0; y < h; ++y)
    std::copy_n(rows.begin() + size_t(h - 1 - y) * w * 3, size_t(w) * 3,
                top_first.begin() + size_t(y) * w * 3);
  write_png_bytes(path, w, h, 3, top_first);
}

void Viewer::save_run(const std::string& path) {
  const std::string line = run_command_line(settings_, options_.program);
  std::ofstream out(path);
  out << line << "\n";
  if (!out) throw UserError("cannot write '" + path + "'");
  message_ = "saved the run command to " + path;
  std::cout << "ldmbench view: " << message_ << ": " << line << std::endl;
}

void Viewer::on_key(int key, int mods) {
  const int step = (mods & GLFW_MOD_SHIFT) ? -1 : 1;
  auto cycle_axis = [&](std::vector<std::string>& axis, const std::vector<std::string>& names) {
    axis = {cycled(names, axis.front(), step)};
    config_dirty_ = true;
  };
  switch (key) {
    case GLFW_KEY_S: cycle_axis(settings_.structures, structure_names()); break;
    case GLFW_KEY_P: cycle_axis(settings_.passes, pass_names()); break;
    case GLFW_KEY_N:
      settings_.views = {std::clamp(step > 0 ? settings_.views.front() * 2 : settings_.views.front() / 2, 1u, 4096u)};
      config_dirty_ = true;
      break;
    case GLFW_KEY_R:
      settings_.resolutions = {std::clamp(step > 0 ? settings_.resolutions.front() * 2 : settings_.resolutions.front() / 2, 1u, 8192u)};
      config_dirty_ = true;
      break;
    case GLFW_KEY_T: {
      std::vector<AoTrace> traces;
      for (const auto& name : ao_trace_names()) traces.push_back(parse_ao_trace(name));
      settings_.traces = {cycled(traces, settings_.traces.front(), step)};
      config_dirty_ = true;
      break;
    }
    case GLFW_KEY_E: {
      std::vector<AoEstimatorChoice> estimators;
      for (const auto& name : ao_estimator_names()) estimators.push_back(parse_ao_estimator(name));
      settings_.estimators = {cycled(estimators, settings_.estimators.front(), step)};
      config_dirty_ = true;
      break;
    }
    case GLFW_KEY_Z: {
      std::vector<SizingPolicy> policies = {SizingPolicy::PreviousFrame, SizingPolicy::Census,
                                            SizingPolicy::Oracle};
      if (settings_.sizing_budget_mib > 0) policies.push_back(SizingPolicy::Budget);
      settings_.sizing = {cycled(policies, settings_.sizing.front(), step)};
      config_dirty_ = true;
      break;
    }
    case GLFW_KEY_1: layout_ = Layout::SideBySide; break;
    case GLFW_KEY_2: layout_ = Layout::Pass; break;
    case GLFW_KEY_3: layout_ = Layout::Reference; break;
    case GLFW_KEY_4: layout_ = Layout::Error; break;
    case GLFW_KEY_5:
    case GLFW_KEY_C: layout_ = layout_ == Layout::Points ? Layout::SideBySide : Layout::Points; break;
    case GLFW_KEY_V: {
      const uint32_t n = settings_.views.front() + 1;  // the last entry: all views
      cloud_view_ = uint32_t((int64_t(cloud_view_) + step + n) % n);
      break;
    }
    case GLFW_KEY_L: colour_by_view_ = !colour_by_view_; break;
    case GLFW_KEY_G: reference_wanted_ = true; break;
    case GLFW_KEY_F: camera_.toggle_mode(); break;
    case GLFW_KEY_H: show_panel_ = !show_panel_; break;
    case GLFW_KEY_F12: {
      const std::string path = "ldmbench-view-" + std::to_string(++screenshot_count_) + ".png";
      save_screenshot(path);
      message_ = "screenshot " + path;
      break;
    }
    case GLFW_KEY_F5: save_run(options_.save_run.empty() ? "ldmbench-view-run.sh" : options_.save_run); break;
    case GLFW_KEY_Q:
    case GLFW_KEY_ESCAPE: glfwSetWindowShouldClose(window_, GLFW_TRUE); break;
    default:
      if (camera_.on_key(key)) camera_dirty_ = true;
  }
}

void Viewer::on_mouse_button(int button, int action) {
  camera_.on_button(button, action == GLFW_PRESS);
}
void Viewer::on_cursor(double x, double y) {
  if (camera_.on_cursor(x, y)) camera_dirty_ = true;
}
void Viewer::on_scroll(double dy) {
  if (camera_.on_scroll(dy)) camera_dirty_ = true;
}

void Viewer::draw_panel() {
  int fb_w = 0, fb_h = 0;
  glfwGetFramebufferSize(window_, &fb_w, &fb_h);
  ImGui::SetNextWindowPos(ImVec2(0, 0));
  ImGui::SetNextWindowSize(ImVec2(kPanelWidth, float(fb_h)));
  ImGui::Begin("ldmbench view", nullptr,
               ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoCollapse);
  auto combo = [&](const char* label, std::vector<std::string>& axis,
                   const std::vector<std::string>& names) {
    if (ImGui::BeginCombo(label, axis.front().c_str())) {
      for (const auto& name : names)
        if (ImGui::Selectable(name.c_str(), name == axis.front())) {
          axis = {name};
          config_dirty_ = true;
        }
      ImGui::EndCombo();
    }
  };
  std::vector<std::string> scenes;
  for (const auto& g : scene_generators()) scenes.push_back(g.name);
  if (std::find(scenes.begin(), scenes.end(), settings_.scenes.front()) == scenes.end())
    scenes.push_back(settings_.scenes.front());
  if (ImGui::CollapsingHeader("Configuration", ImGuiTreeNodeFlags_DefaultOpen)) {
    combo("scene", settings_.scenes, scenes);
    combo("structure (S)", settings_.structures, structure_names());
    combo("pass (P)", settings_.passes, pass_names());
    int n = int(settings_.views.front()), r = int(settings_.resolutions.front());
    if (ImGui::InputInt("N (N)", &n, 1, 8, ImGuiInputTextFlags_EnterReturnsTrue)) {
      settings_.views = {uint32_t(std::clamp(n, 1, 4096))};
      config_dirty_ = true;
    }
    if (ImGui::InputInt("R_LDM (R)", &r, 8, 64, ImGuiInputTextFlags_EnterReturnsTrue)) {
      settings_.resolutions = {uint32_t(std::clamp(r, 1, 8192))};
      config_dirty_ = true;
    }
    std::vector<std::string> trace = {ao_trace_name(settings_.traces.front())};
    combo("trace (T)", trace, ao_trace_names());
    settings_.traces = {parse_ao_trace(trace.front())};
    std::vector<std::string> estimator = {ao_estimator_name(settings_.estimators.front())};
    combo("estimator (E)", estimator, ao_estimator_names());
    settings_.estimators = {parse_ao_estimator(estimator.front())};
    std::vector<std::string> visibility = {visibility_name(settings_.visibility.front())};
    combo("visibility", visibility, {"scene", "attenuated", "unattenuated"});
    settings_.visibility = {visibility.front() == "attenuated"     ? Visibility::Attenuated
                            : visibility.front() == "unattenuated" ? Visibility::Unattenuated
                                                                   : Visibility::Scene};
    std::vector<std::string> sizing = {sizing_policy_name(settings_.sizing.front())};
    combo("sizing (Z)", sizing, {"previous_frame", "census", "oracle", "budget"});
    settings_.sizing = {parse_sizing_policy(sizing.front())};
    if (settings_.sizing.front() == SizingPolicy::Budget) {
      double mib = settings_.sizing_budget_mib;
      if (ImGui::InputDouble("budget MiB", &mib, 1, 16, "%.3f", ImGuiInputTextFlags_EnterReturnsTrue)) {
        settings_.sizing_budget_mib = std::max(0.001, mib);
        config_dirty_ = true;
      }
    }
    bool own_d_max = !settings_.d_max.empty();
    if (ImGui::Checkbox("d_max", &own_d_max)) {
      settings_.d_max.clear();
      if (own_d_max) settings_.d_max = {scene_ ? scene_->ao.d_max : 1.0f};
      config_dirty_ = true;
    }
    if (own_d_max) {
      ImGui::SameLine();
      float d = settings_.d_max.front();
      if (ImGui::InputFloat("##dmax", &d, 0, 0, "%.4g", ImGuiInputTextFlags_EnterReturnsTrue) && d > 0) {
        settings_.d_max = {d};
        config_dirty_ = true;
      }
    }
    bool own_offset = settings_.normal_offset_pixels.has_value();
    if (ImGui::Checkbox("normal offset px", &own_offset)) {
      settings_.normal_offset_pixels.reset();
      if (own_offset) settings_.normal_offset_pixels = scene_ ? scene_->ao.normal_offset_pixels : 0.5f;
      config_dirty_ = true;
    }
    if (own_offset) {
      ImGui::SameLine();
      float o = *settings_.normal_offset_pixels;
      if (ImGui::InputFloat("##offset", &o, 0, 0, "%.4g", ImGuiInputTextFlags_EnterReturnsTrue) && o >= 0) {
        settings_.normal_offset_pixels = o;
        config_dirty_ = true;
      }
    }
    // Structure and pass parameters, as --param OWNER:KEY=VALUE lines: checked by the
    // structure or pass itself when applied (an error shows below).
    if (!param_text_loaded_) {
      param_text_.clear();
      for (const auto& [owner, params] : settings_.structure_params)
        for (const auto& [key, value] : params) param_text_ += owner + ":" + key + "=" + value + "\n";
      param_text_.resize(param_text_.size() + 1024, '\0');
      param_text_loaded_ = true;
    }
    ImGui::TextUnformatted("parameters (OWNER:KEY=VALUE per line)");
    ImGui::InputTextMultiline("##params", param_text_.data(), param_text_.size(),
                              ImVec2(-1, 36));
    if (ImGui::Button("apply parameters")) {
      std::map<std::string, std::map<std::string, std::string>> params;
      std::istringstream lines(param_text_.c_str());
      std::string line;
      message_.clear();
      while (std::getline(lines, line)) {
        if (line.empty()) continue;
        const auto colon = line.find(':'), equals = line.find('=');
        if (colon == std::string::npos || equals == std::string::npos || equals < colon) {
          message_ = "not OWNER:KEY=VALUE: " + line;
          break;
        }
        params[line.substr(0, colon)][line.substr(colon + 1, equals - colon - 1)] =
            line.substr(equals + 1);
      }
      if (message_.empty()) {
        settings_.structure_params = params;
        config_dirty_ = true;
      }
    }
  }
  if (ImGui::CollapsingHeader("Display", ImGuiTreeNodeFlags_DefaultOpen)) {
    int layout = int(layout_);
    ImGui::RadioButton("side by side (1)", &layout, int(Layout::SideBySide));
    ImGui::RadioButton("pass (2)", &layout, int(Layout::Pass));
    ImGui::SameLine();
    ImGui::RadioButton("reference (3)", &layout, int(Layout::Reference));
    ImGui::RadioButton("error (4)", &layout, int(Layout::Error));
    ImGui::SameLine();
    ImGui::RadioButton("point cloud (C)", &layout, int(Layout::Points));
    layout_ = Layout(layout);
    if (layout_ == Layout::Points) {
      int view = int(cloud_view_);
      const int n = int(settings_.views.front());
      ImGui::SliderInt("LDM view (V)", &view, 0, n, view == n ? "all" : "%d");
      cloud_view_ = uint32_t(view);
      ImGui::Checkbox("colour by view (L)", &colour_by_view_);
      ImGui::SliderFloat("point size", &point_size_, 1.0f, 8.0f);
      int layers = int(cloud_layers_);
      if (ImGui::SliderInt("layers", &layers, 1, 256)) cloud_layers_ = uint32_t(layers);
      ImGui::Text("points %llu of %llu stored (%u layers)", (unsigned long long)cloud_counts_.shown,
                  (unsigned long long)cloud_counts_.stored, cloud_counts_.layers);
    }
    ImGui::Text("camera: %s (F), drag to turn, wheel to zoom%s", camera_.mode_name(),
                camera_.is_fly() ? ", arrows to move" : "");
    if (ImGui::Button("reference (G)")) reference_wanted_ = true;
    ImGui::SameLine();
    if (ImGui::Button("screenshot (F12)")) on_key(GLFW_KEY_F12, 0);
    ImGui::SameLine();
    if (ImGui::Button("save as run (F5)")) on_key(GLFW_KEY_F5, 0);
    ImGui::TextWrapped("reference: %s", reference_status_.c_str());
    if (!message_.empty()) ImGui::TextWrapped("%s", message_.c_str());
  }
  if (ImGui::CollapsingHeader("Measurement", ImGuiTreeNodeFlags_DefaultOpen)) {
    ImGui::TextWrapped("%s", device_.gl_renderer.c_str());
    if (!error_.empty()) ImGui::TextColored(ImVec4(1, 0.4f, 0.3f, 1), "%s", error_.c_str());
    if (have_measurement_) {
      const Measurement& m = measurement_;
      const ImVec4 colour = m.status == BuildStatus::Ok      ? ImVec4(0.4f, 1, 0.4f, 1)
                            : m.status == BuildStatus::Lossy ? ImVec4(1, 0.8f, 0.3f, 1)
                                                             : ImVec4(1, 0.3f, 0.3f, 1);
      ImGui::TextColored(colour, "status %s", build_status_name(m.status));
      if (!m.status_detail.empty()) ImGui::TextWrapped("%s", m.status_detail.c_str());
      ImGui::Text("%s  frames kept %zu, timer %s", config_.id().c_str(), m.frames.size(),
                  timer_source_name(m.timer));
      ImGui::Text("fragments %llu, stored %llu, lost %llu", (unsigned long long)m.census.fragments,
                  (unsigned long long)m.last_build.fragments_stored,
                  (unsigned long long)m.last_build.fragments_lost);
      ImGui::Text("depth complexity max %u, mean %.2f, rebuilds %llu", m.census.max_depth_complexity,
                  m.census.mean_depth_complexity, (unsigned long long)m.sizing_rebuilds);
      if (comparison_)
        ImGui::Text("MSE %.4g  PSNR %.2f dB  MSSIM %.4f", comparison_->mse, comparison_->psnr,
                    comparison_->mssim);
      const auto summaries = m.summaries();
      if (ImGui::BeginTable("times", 3, ImGuiTableFlags_Borders)) {
        ImGui::TableSetupColumn("sub-pass");
        ImGui::TableSetupColumn("last ms");
        ImGui::TableSetupColumn("median ms");
        ImGui::TableHeadersRow();
        for (const auto& [name, ms] : last_times_) {
          ImGui::TableNextColumn();
          ImGui::TextUnformatted(name.c_str());
          ImGui::TableNextColumn();
          ImGui::Text("%.3f", ms);
          ImGui::TableNextColumn();
          const TimingSummary* s = find_summary(summaries, name);
          if (s) ImGui::Text("%.3f", s->median);
        }
        ImGui::EndTable();
      }
      if (ImGui::BeginTable("memory", 3, ImGuiTableFlags_Borders)) {
        ImGui::TableSetupColumn("buffer");
        ImGui::TableSetupColumn("allocated");
        ImGui::TableSetupColumn("used");
        ImGui::TableHeadersRow();
        for (const auto& b : m.memory) {
          ImGui::TableNextColumn();
          ImGui::TextUnformatted(b.name.c_str());
          ImGui::TableNextColumn();
          ImGui::TextUnformatted(format_bytes(b.allocated).c_str());
          ImGui::TableNextColumn();
          ImGui::TextUnformatted(format_bytes(b.used).c_str());
        }
        ImGui::TableNextColumn();
        ImGui::TextUnformatted("total");
        ImGui::TableNextColumn();
        ImGui::TextUnformatted(format_bytes(m.bytes_allocated()).c_str());
        ImGui::TableNextColumn();
        ImGui::TextUnformatted(format_bytes(m.bytes_used()).c_str());
        ImGui::EndTable();
      }
    }
  }
  ImGui::End();
}

int Viewer::run() {
  while (!glfwWindowShouldClose(window_)) {
    glfwPollEvents();
    for (const KeyPress& press : script_)
      if (press.frame == frame_) on_key(press.key, press.mods);
    run_frame();
    if (reference_wanted_ && session_) {
      reference_wanted_ = false;
      request_reference();
    }
    // A script's last frame shows the reference it asked for (G): wait for it there.
    const bool last_frame = options_.frames > 0 && frame_ + 1 >= options_.frames;
    if (last_frame && reference_job_.valid()) reference_job_.wait();
    update_reference();

    ImGui_ImplOpenGL3_NewFrame();
    ImGui_ImplGlfw_NewFrame();
    ImGui::NewFrame();
    int fb_w = 0, fb_h = 0;
    glfwGetFramebufferSize(window_, &fb_w, &fb_h);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glViewport(0, 0, fb_w, fb_h);
    glClearColor(0.12f, 0.12f, 0.14f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    draw_images(fb_w, fb_h);
    if (show_panel_) draw_panel();
    ImGui::Render();
    glViewport(0, 0, fb_w, fb_h);
    ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
    if (options_.print_status) print_status();
    ++frame_;
    const bool last = options_.frames > 0 && frame_ >= options_.frames;
    if (last && !options_.screenshot.empty()) save_screenshot(options_.screenshot);
    glfwSwapBuffers(window_);
    if (last) break;
  }
  if (!options_.save_run.empty()) save_run(options_.save_run);
  std::cout.flush();
  // A reference still rendering on the CPU cannot be stopped; the process ends without it.
  if (reference_job_.valid() &&
      reference_job_.wait_for(std::chrono::seconds(0)) != std::future_status::ready)
    std::_Exit(error_.empty() || have_measurement_ ? kExitOk : 1);
  return error_.empty() || have_measurement_ ? kExitOk : 1;
}

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
