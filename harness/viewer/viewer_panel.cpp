// The viewer's ImGui panel: the configuration's controls, the display's, and the figures
// of the session's Measurement.
#include "harness/viewer/viewer_app.h"

#include <algorithm>
#include <cstdio>
#include <sstream>

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <imgui.h>

#include "harness/settings/harness_axes.h"
#include "harness/measuring/timing_columns.h"
#include "harness/passes/pass.h"
#include "harness/records/harness_columns.h"
#include "harness/scene/generators.h"
#include "ldm_impls/ldm_structure.h"

namespace ldm::viewer {
namespace {

std::string format_bytes(uint64_t bytes) {
  char b[32];
  if (bytes >= (1u << 20))
    std::snprintf(b, sizeof b, "%.2f MiB", double(bytes) / double(1u << 20));
  else
    std::snprintf(b, sizeof b, "%.1f KiB", double(bytes) / 1024.0);
  return b;
}

}  // namespace

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
    // Choices and ranges from the axes' declarations (harness/settings/harness_axes.cpp).
    auto choices = [](const char* key) { return axis_choices(find_harness_axis(key)->spec); };
    auto clamped = [](const char* key, int v) {
      const AxisSpec& spec = find_harness_axis(key)->spec;
      return uint32_t(std::clamp(v, int(spec.min), int(spec.max)));
    };
    combo("structure (S)", settings_.structures, choices("structures"));
    combo("pass (P)", settings_.passes, choices("passes"));
    int n = int(settings_.views.front()), r = int(settings_.resolutions.front());
    if (ImGui::InputInt("N (N)", &n, 1, 8, ImGuiInputTextFlags_EnterReturnsTrue)) {
      settings_.views = {clamped("views", n)};
      config_dirty_ = true;
    }
    if (ImGui::InputInt("R_LDM (R)", &r, 8, 64, ImGuiInputTextFlags_EnterReturnsTrue)) {
      settings_.resolutions = {clamped("r_ldm", r)};
      config_dirty_ = true;
    }
    std::vector<std::string> trace = {ao_trace_name(settings_.traces.front())};
    combo("trace (T)", trace, choices("trace"));
    settings_.traces = {parse_ao_trace(trace.front())};
    std::vector<std::string> estimator = {ao_estimator_name(settings_.estimators.front())};
    combo("estimator (E)", estimator, choices("ao_estimator"));
    settings_.estimators = {parse_ao_estimator(estimator.front())};
    std::vector<std::string> visibility = {visibility_name(settings_.visibility.front())};
    combo("visibility", visibility, choices("visibility"));
    settings_.visibility = {visibility.front() == "attenuated"     ? Visibility::Attenuated
                            : visibility.front() == "unattenuated" ? Visibility::Unattenuated
                                                                   : Visibility::Scene};
    std::vector<std::string> sizing = {sizing_policy_name(settings_.sizing.front())};
    combo("sizing (Z)", sizing, choices("sizing"));
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
      using namespace columns;
      const BuildStatus status = m.status();
      const ImVec4 colour = status == BuildStatus::Ok      ? ImVec4(0.4f, 1, 0.4f, 1)
                            : status == BuildStatus::Lossy ? ImVec4(1, 0.8f, 0.3f, 1)
                                                           : ImVec4(1, 0.3f, 0.3f, 1);
      ImGui::TextColored(colour, "status %s", build_status_name(status));
      const std::string detail = m.status_detail();
      if (!detail.empty()) ImGui::TextWrapped("%s", detail.c_str());
      ImGui::Text("%s  frames kept %zu, timer %s", config_.id().c_str(), m.frames.size(),
                  m.columns.text(kTimer).c_str());
      ImGui::Text("fragments %llu, stored %llu, lost %llu", (unsigned long long)m.count(kFragments),
                  (unsigned long long)m.count(kFragmentsStored), (unsigned long long)m.count(kFragmentsLost));
      ImGui::Text("depth complexity max %llu, mean %.2f, rebuilds %llu",
                  (unsigned long long)m.count(kMaxDepthComplexity), m.number(kMeanDepthComplexity),
                  (unsigned long long)m.count(kSizingRebuilds));
      if (comparison_)
        ImGui::Text("MSE %.4g  PSNR %.2f dB  MSSIM %.4f", comparison_->mse, comparison_->psnr,
                    comparison_->mssim);
      const auto summaries = m.summaries();
      if (ImGui::BeginTable("times", 3, ImGuiTableFlags_Borders)) {
        ImGui::TableSetupColumn("sub-pass");
        ImGui::TableSetupColumn("last ms");
        ImGui::TableSetupColumn("median ms, 95% interval");
        ImGui::TableHeadersRow();
        for (const auto& [name, ms] : last_times_) {
          ImGui::TableNextColumn();
          ImGui::TextUnformatted(name.c_str());
          ImGui::TableNextColumn();
          ImGui::Text("%.3f", ms);
          ImGui::TableNextColumn();
          // The median to the digits its interval supports, with the relative half-width;
          // the interval widens the moment the camera moves (those frames differ).
          const TimingSummary* s = find_summary(summaries, name);
          if (s)
            ImGui::TextUnformatted(
                format_time_with_interval(s->median, s->interval.low, s->interval.high).c_str());
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
        ImGui::TextUnformatted(format_bytes(m.count(columns::kBytesAllocated)).c_str());
        ImGui::TableNextColumn();
        ImGui::TextUnformatted(format_bytes(m.count(columns::kBytesUsed)).c_str());
        ImGui::EndTable();
      }
    }
  }
  ImGui::End();
}

}  // namespace ldm::viewer
