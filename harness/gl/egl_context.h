#pragma once
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "harness/gl/device_selection.h"

namespace ldm {

// Which EGL platform to open. Auto picks an NVIDIA GPU through the EGL device platform when
// there is one (the CUDA ordinal `gpu` asks for, default 0), otherwise Mesa's surfaceless
// platform (llvmpipe on machines without a GPU), or the device `gpu` asks for when given.
enum class EglPlatform { Auto, Device, Surfaceless };

struct ContextOptions {
  EglPlatform platform = EglPlatform::Auto;
  bool debug_output = false;  // GL_KHR_debug messages (errors, warnings) to stderr
  // --gpu N or LDM_GPU=N (device_selection.h); nullopt: the default device.
  std::optional<GpuRequest> gpu;
};

// Debug builds turn GL debug output on; release builds leave it to --gl-debug.
inline ContextOptions default_context_options() {
  ContextOptions options;
#ifndef NDEBUG
  options.debug_output = true;
#endif
  return options;
}

// What the context runs on; copied into every record.
struct DeviceInfo {
  std::string egl_platform;  // "device" or "surfaceless"
  std::string egl_vendor;
  std::string gl_renderer;
  std::string gl_vendor;
  std::string gl_version;
  std::string glsl_version;
  int gl_major = 0;
  int gl_minor = 0;
  int64_t max_ssbo_block_bytes = 0;  // GL_MAX_SHADER_STORAGE_BLOCK_SIZE
  int64_t max_ssbo_bindings = 0;
  bool has_int64_atomics = false;  // GL_NV_shader_atomic_int64 (64-bit atomicMax on SSBOs)
  bool has_timer_queries = false;  // timestamp counter with > 0 bits
  bool debug_output = false;
  // What the driver self-tests found wrong (harness/gl/driver_probe.h): "none", or each
  // failed probe.
  std::string driver_defects;
  // Which device it is: a unique name (device_selection.h, device_id()), the driver's short
  // name (llvmpipe, zink, nvidia, ...), and how it was chosen (printed, not recorded).
  std::string device_id;
  std::string gl_driver;
  std::string device_choice;
};

// Every EGL device (EGL_EXT_device_enumeration), each tried for an OpenGL 4.5 core context
// when `try_contexts` (its renderer then filled in): what `ldmbench info` lists.
std::vector<EglDeviceSummary> list_egl_devices(bool try_contexts);

// An OpenGL 4.5 core context with no window, current on the calling thread for its lifetime.
// Rendering goes into framebuffer objects. Throws UserError with what was found when the
// device cannot give OpenGL 4.5 core.
class HeadlessContext {
 public:
  static std::unique_ptr<HeadlessContext> create(const ContextOptions& options = {});
  ~HeadlessContext();
  HeadlessContext(const HeadlessContext&) = delete;
  HeadlessContext& operator=(const HeadlessContext&) = delete;

  const DeviceInfo& device() const { return device_; }
  bool has_extension(const std::string& name) const;

 private:
  HeadlessContext() = default;
  void* display_ = nullptr;
  void* context_ = nullptr;
  DeviceInfo device_;
};

// What the OpenGL context current on this thread runs on, whoever created it (the headless
// EGL context above, or a window's context in `ldmbench view`). `platform_name` goes into
// DeviceInfo::egl_platform. Throws UserError below OpenGL 4.5; turns debug output on when
// asked. The library's GL code runs on any such context: GL entry points come from libglvnd's
// libOpenGL, which dispatches to whichever context is current (gl_api.h).
DeviceInfo describe_current_context(const std::string& platform_name, bool debug_output);
bool has_gl_extension(const std::string& name);  // of the current context

EglPlatform parse_egl_platform(const std::string& name);  // "auto" | "device" | "surfaceless"

}  // namespace ldm
