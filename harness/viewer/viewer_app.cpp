#include "harness/viewer/viewer_app.h"

// The frame loop of the viewer (viewer_app.h). GLFW includes no GL header of its own: ldmbench's (libglvnd's core profile) comes first.
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
#include <filesystem>
#include <fstream>
#include <future>
#include <iostream>
#include <memory>
#include <sstream>

#include <glm/gtc/matrix_transform.hpp>

#include "harness/records/harness_columns.h"
#include "harness/measuring/ldm_setup.h"
#include "harness/measuring/measure_configuration.h"
#include "harness/measuring/measurement_session.h"
#include "harness/run/exit_codes.h"
#include "harness/settings/run_command_line.h"
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
#include "harness/util/text.h"
#include "harness/viewer/camera_control.h"
#include "harness/viewer/key_script.h"
#include "harness/viewer/point_cloud.h"

namespace ldm::viewer {
namespace {

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

// The values `parse` makes of `names` (an axis's choices in the order it lists them).
template <typename T>
std::vector<T> parsed(const std::vector<std::string>& names, T (*parse)(const std::string&)) {
  std::vector<T> values;
  for (const auto& name : names) values.push_back(parse(name));
  return values;
}

}  // namespace

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
    line << " status=" << m.columns.text(columns::kStatus) << " fragments=" << m.count(columns::kFragments)
         << " stored=" << m.count(columns::kFragmentsStored) << " lost=" << m.count(columns::kFragmentsLost)
         << " bytes_allocated=" << m.count(columns::kBytesAllocated);
    for (const auto& [name, ms] : last_times_)
      if (name == "build" || name == "frame") line << " " << name << "_ms=" << format_significant(ms, 4);
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
  // The same configuration as a sweep file beside it, for `ldmbench sweep`.
  const std::string sweep_path =
      (std::filesystem::path(path).replace_extension("").string()) + ".sweep.json";
  std::ofstream sweep(sweep_path);
  sweep << sweep_file_json(settings_, "saved by ldmbench view");
  if (!sweep) throw UserError("cannot write '" + sweep_path + "'");
  message_ = "saved the run command to " + path + " and the sweep file " + sweep_path;
  std::cout << "ldmbench view: " << message_ << ": " << line << std::endl;
}

void Viewer::on_key(int key, int mods) {
  const int step = (mods & GLFW_MOD_SHIFT) ? -1 : 1;
  // Sets a single-valued axis to the value `step` on from its own in `values`.
  auto cycle_axis = [&](auto& axis, const auto& values) {
    axis = {cycled(values, axis.front(), step)};
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
    case GLFW_KEY_T: cycle_axis(settings_.traces, parsed(ao_trace_names(), parse_ao_trace)); break;
    case GLFW_KEY_E:
      cycle_axis(settings_.estimators, parsed(ao_estimator_names(), parse_ao_estimator));
      break;
    case GLFW_KEY_Z: {
      std::vector<SizingPolicy> policies = {SizingPolicy::PreviousFrame, SizingPolicy::Census,
                                            SizingPolicy::Oracle};
      if (settings_.sizing_budget_mib > 0) policies.push_back(SizingPolicy::Budget);
      cycle_axis(settings_.sizing, policies);
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

}  // namespace ldm::viewer
