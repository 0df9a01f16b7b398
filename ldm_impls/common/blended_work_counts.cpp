#include "ldm_impls/common/blended_work_counts.h"

#include <algorithm>
#include <cstdlib>
#include <regex>
#include <set>
#include <sstream>

#include "harness/gl/bindings.h"
#include "harness/measure/work_counters.h"
#include "harness/util/error.h"

namespace ldm {

namespace {

// Whether the shader's main() starts with LDM_SKIP_HELPER_INVOCATIONS, which zeroes the
// blended outputs before anything adds to them (an output never written is undefined, and
// would be blended as it is).
bool main_starts_by_skipping_helpers(const std::string& source) {
  static const std::regex start(R"(void\s+main\s*\(\s*\)\s*\{\s*LDM_SKIP_HELPER_INVOCATIONS\s*;)");
  return std::regex_search(source, start);
}

// The names work_add(name, ...) adds to in `source`, in order of first appearance.
std::vector<std::string> added_names(const std::string& source) {
  static const std::regex site(R"(work_add\(\s*([A-Za-z_][A-Za-z0-9_]*)\s*,)");
  std::vector<std::string> names;
  for (auto it = std::sregex_iterator(source.begin(), source.end(), site); it != std::sregex_iterator(); ++it)
    if (std::find(names.begin(), names.end(), (*it)[1].str()) == names.end()) names.push_back((*it)[1].str());
  return names;
}

// The counters the counting replay declares: its defines' WORK_<name> slots.
std::set<std::string> declared_counters(const std::string& source) {
  static const std::regex slot(R"(#define WORK_([A-Za-z_][A-Za-z0-9_]*) )");
  std::set<std::string> names;
  for (auto it = std::sregex_iterator(source.begin(), source.end(), slot); it != std::sregex_iterator(); ++it)
    names.insert((*it)[1].str());
  return names;
}

int max_draw_buffers() {
  GLint n = 0;
  glGetIntegerv(GL_MAX_DRAW_BUFFERS, &n);
  return n;
}

}  // namespace

BlendedTotals blended_totals_of(const std::string& fragment_file, const ShaderDefines& defines,
                                uint32_t resolution) {
  if (!WorkCountingScope::blending_totals()) return {};
  const std::string source = preprocess_shader(fragment_file, defines, {}, nullptr);
  if (!main_starts_by_skipping_helpers(source)) return {};
  const std::set<std::string> declared = declared_counters(source);
  BlendedTotals totals;
  for (const auto& name : added_names(source))
    if (declared.count(name)) totals.names.push_back(name);
  const uint64_t bytes = uint64_t(totals.targets()) * resolution * resolution * 16;
  if (totals.targets() > max_draw_buffers() || bytes > kMaxBlendedTargetBytes) return {};
  return totals;
}

ShaderDefines blend_defines(const BlendedTotals& totals) {
  ShaderDefines d;
  d.set("WORK_BLEND_TARGETS", totals.targets());
  for (size_t i = 0; i < totals.names.size(); ++i) d.set("WORK_CHANNEL_" + totals.names[i], (long long)i);
  return d;
}

uint32_t blended_exact_limit() {
  static const uint32_t limit = [] {
    constexpr uint32_t exact = uint32_t(1) << 24;
    const char* text = std::getenv("LDM_WORK_BLEND_EXACT_LIMIT");
    if (!text || !*text) return exact;
    char* end = nullptr;
    const unsigned long value = std::strtoul(text, &end, 10);
    if (*end != '\0' || value == 0 || value > exact)
      throw UserError(std::string("LDM_WORK_BLEND_EXACT_LIMIT: expected an integer from 1 to 16777216, got \"") +
                      text + "\"");
    return uint32_t(value);
  }();
  return limit;
}

BlendedWorkTargets::BlendedWorkTargets(uint32_t resolution, BlendedTotals totals)
    : resolution_(resolution), totals_(std::move(totals)),
      largest_("blended work counts: largest pixel", sizeof(uint32_t)) {
  std::vector<GLenum> draw_buffers;
  for (int t = 0; t < totals_.targets(); ++t) {
    targets_.emplace_back(GL_RGBA32F, int(resolution), int(resolution));
    framebuffer_.attach_color(t, targets_.back());
    draw_buffers.push_back(GLenum(GL_COLOR_ATTACHMENT0 + t));
  }
  glNamedFramebufferDrawBuffers(framebuffer_.id(), GLsizei(draw_buffers.size()), draw_buffers.data());
  framebuffer_.check_complete("blended work counts");
  std::string slots;
  for (const auto& name : totals_.names) slots += (slots.empty() ? "" : ", ") + ("uint(WORK_" + name + ")");
  ShaderDefines defines = binding_defines();
  defines.set("LDM_BLENDED_LARGEST_BINDING", kBlendedLargestBinding);
  defines.set("BLEND_CHANNELS", (long long)totals_.names.size());
  defines.set("BLEND_SLOTS", slots);
  sum_program_ = build_program({{GL_COMPUTE_SHADER, "ldm/common/blended_work_sum.comp", {}}}, defines);
  check_gl("blended work counts");
}

void BlendedWorkTargets::begin() const {
  const float zero[4] = {0, 0, 0, 0};
  for (int t = 0; t < totals_.targets(); ++t) glClearNamedFramebufferfv(framebuffer_.id(), GL_COLOR, t, zero);
  glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_.id());
  glEnable(GL_BLEND);
  glBlendEquation(GL_FUNC_ADD);
  glBlendFunc(GL_ONE, GL_ONE);
}

void BlendedWorkTargets::end_and_sum() const {
  glDisable(GL_BLEND);
  const UncountedGpuWork counting_own_work;  // not the build's: out of the driver's statistics
  glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);
  largest_.clear_to_zero();
  sum_program_.use();
  sum_program_.set("resolution", int(resolution_));
  largest_.bind_storage(kBlendedLargestBinding);
  for (int t = 0; t < totals_.targets(); ++t) {
    glBindTextureUnit(0, targets_[t].id());
    sum_program_.set("first_channel", 4 * t);
    glDispatchCompute(GLuint((resolution_ + 63) / 64), 1, 1);
  }
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
  uint32_t largest = 0;
  largest_.download(&largest, sizeof largest);
  if (largest >= blended_exact_limit()) {
    std::string names;
    for (const auto& name : totals_.names) names += (names.empty() ? "" : ", ") + name;
    WorkCountingScope::report_inexact_blend("a pixel's blended total reached " + std::to_string(largest) +
                                            " (exact below " + std::to_string(blended_exact_limit()) +
                                            "; counting " + names + ")");
  }
  check_gl("blended work counts: sum");
}

}  // namespace ldm
