#include "harness/gl/driver_probe.h"

#include <map>
#include <mutex>

#include "harness/gl/gl_objects.h"
#include "harness/gl/shader_program.h"

namespace ldm {
namespace {

constexpr uint32_t kComputeInvocations = 64;  // one work group: 8 SIMD vectors on llvmpipe
constexpr int kFragmentSide = 16;             // 256 fragments
constexpr uint32_t kMarksBinding = 0;

ShaderDefines probe_defines(ProbeBarrier barrier, bool drop_some) {
  ShaderDefines d;
  d.set("PROBE_MARKS_BINDING", kMarksBinding);
  d.set("PROBE_INVOCATIONS", kComputeInvocations);
  d.set("PROBE_SIDE", kFragmentSide);
  d.set("PROBE_BARRIER()", barrier == ProbeBarrier::MemoryBarrier ? "memoryBarrier()"
                                                                   : "memoryBarrierBuffer()");
  d.set("PROBE_DROP_SOME", drop_some ? 1 : 0);
  return d;
}

uint32_t count_marked(const GlBuffer& marks, uint32_t invocations) {
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  std::vector<uint32_t> words(invocations);
  marks.download(words.data(), words.size() * sizeof(uint32_t));
  uint32_t marked = 0;
  for (uint32_t w : words) marked += w == 1u;
  return marked;
}

}  // namespace

const char* probe_stage_name(ProbeStage stage) {
  return stage == ProbeStage::Compute ? "compute" : "fragment";
}

const char* probe_barrier_name(ProbeBarrier barrier) {
  return barrier == ProbeBarrier::MemoryBarrier ? "memoryBarrier()" : "memoryBarrierBuffer()";
}

std::string BarrierProbeResult::describe() const {
  return std::string(probe_barrier_name(barrier)) + " in a divergent " + probe_stage_name(stage) +
         " loop: " + std::to_string(invocations - completed) + " of " +
         std::to_string(invocations) + " invocations lost";
}

BarrierProbeResult probe_barrier_in_divergent_loop(ProbeStage stage, ProbeBarrier barrier,
                                                   bool drop_some) {
  BarrierProbeResult result;
  result.stage = stage;
  result.barrier = barrier;
  const ShaderDefines defines = probe_defines(barrier, drop_some);
  if (stage == ProbeStage::Compute) {
    result.invocations = kComputeInvocations;
    GlBuffer marks("probe marks", result.invocations * sizeof(uint32_t));
    marks.clear_to_zero();
    const GlProgram program =
        build_program({{GL_COMPUTE_SHADER, "probes/barrier_in_divergent_loop.comp", {}}}, defines);
    marks.bind_storage(kMarksBinding);
    program.use();
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    glDispatchCompute(1, 1, 1);
    result.completed = count_marked(marks, result.invocations);
  } else {
    result.invocations = uint32_t(kFragmentSide * kFragmentSide);
    GlBuffer marks("probe marks", result.invocations * sizeof(uint32_t));
    marks.clear_to_zero();
    const GlProgram program =
        build_program({{GL_VERTEX_SHADER, "passes/fullscreen.vert", {}},
                       {GL_FRAGMENT_SHADER, "probes/barrier_in_divergent_loop.frag", {}}},
                      defines);
    GlFramebuffer framebuffer;
    framebuffer.set_default_size(kFragmentSide, kFragmentSide);
    const GlVertexArray vertex_array;
    GLint viewport[4];
    glGetIntegerv(GL_VIEWPORT, viewport);
    glBindFramebuffer(GL_FRAMEBUFFER, framebuffer.id());
    glViewport(0, 0, kFragmentSide, kFragmentSide);
    marks.bind_storage(kMarksBinding);
    program.use();
    glBindVertexArray(vertex_array.id());
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glBindVertexArray(0);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glViewport(viewport[0], viewport[1], viewport[2], viewport[3]);
    result.completed = count_marked(marks, result.invocations);
  }
  check_gl("barrier probe");
  return result;
}

const BarrierProbeResult* DriverConformance::barrier_defect(ProbeStage stage,
                                                            ProbeBarrier barrier) const {
  for (const BarrierProbeResult& probe : barrier_probes)
    if (probe.stage == stage && probe.barrier == barrier && !probe.conformant()) return &probe;
  return nullptr;
}

std::string DriverConformance::defects_text() const {
  std::string text;
  for (const BarrierProbeResult& probe : barrier_probes)
    if (!probe.conformant()) text += (text.empty() ? "" : "; ") + probe.describe();
  return text.empty() ? "none" : text;
}

const DriverConformance& driver_conformance() {
  static std::mutex mutex;
  static std::map<std::string, DriverConformance> by_driver;
  const auto text = [](GLenum name) {
    const char* s = reinterpret_cast<const char*>(glGetString(name));
    return std::string(s ? s : "");
  };
  const std::string driver = text(GL_RENDERER) + " | " + text(GL_VERSION);
  const std::lock_guard<std::mutex> lock(mutex);
  auto found = by_driver.find(driver);
  if (found != by_driver.end()) return found->second;
  DriverConformance conformance;
  for (ProbeStage stage : {ProbeStage::Compute, ProbeStage::Fragment})
    for (ProbeBarrier barrier : {ProbeBarrier::MemoryBarrier, ProbeBarrier::MemoryBarrierBuffer})
      conformance.barrier_probes.push_back(probe_barrier_in_divergent_loop(stage, barrier));
  return by_driver.emplace(driver, std::move(conformance)).first->second;
}

}  // namespace ldm
