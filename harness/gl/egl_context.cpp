#include "harness/gl/egl_context.h"

#include <EGL/egl.h>
#include <EGL/eglext.h>

#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "harness/gl/driver_probe.h"
#include "harness/gl/gl_api.h"
#include "harness/util/error.h"

namespace ldm {
namespace {

template <typename Fn>
Fn egl_proc(const char* name) {
  return reinterpret_cast<Fn>(eglGetProcAddress(name));
}

std::string egl_error_string(EGLint code) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "EGL error 0x%04x", static_cast<unsigned>(code));
  return buffer;
}

bool contains_word(const char* list, const char* word) {
  if (!list) return false;
  const size_t n = std::strlen(word);
  for (const char* p = std::strstr(list, word); p; p = std::strstr(p + 1, word)) {
    const bool starts = p == list || p[-1] == ' ';
    const bool ends = p[n] == '\0' || p[n] == ' ';
    if (starts && ends) return true;
  }
  return false;
}

// Finds an NVIDIA GPU among the EGL devices (the proprietary driver marks its devices with
// EGL_NV_device_cuda). Returns nullptr when there is none.
EGLDeviceEXT find_nvidia_device() {
  auto query_devices = egl_proc<PFNEGLQUERYDEVICESEXTPROC>("eglQueryDevicesEXT");
  auto query_string = egl_proc<PFNEGLQUERYDEVICESTRINGEXTPROC>("eglQueryDeviceStringEXT");
  if (!query_devices || !query_string) return nullptr;
  EGLint count = 0;
  if (!query_devices(0, nullptr, &count) || count <= 0) return nullptr;
  std::vector<EGLDeviceEXT> devices(static_cast<size_t>(count));
  query_devices(count, devices.data(), &count);
  for (EGLDeviceEXT device : devices) {
    if (contains_word(query_string(device, EGL_EXTENSIONS), "EGL_NV_device_cuda")) return device;
  }
  return nullptr;
}

void APIENTRY debug_callback(GLenum source, GLenum type, GLuint id, GLenum severity, GLsizei,
                               const GLchar* message, const void*) {
  (void)source;
  if (severity == GL_DEBUG_SEVERITY_NOTIFICATION) return;
  std::fprintf(stderr, "[gl debug] type 0x%x id %u severity 0x%x: %s\n", type, id, severity,
               message);
}

}  // namespace

EglPlatform parse_egl_platform(const std::string& name) {
  if (name == "auto") return EglPlatform::Auto;
  if (name == "device") return EglPlatform::Device;
  if (name == "surfaceless") return EglPlatform::Surfaceless;
  throw UserError("--egl-platform: expected auto, device or surfaceless, got '" + name + "'");
}

std::unique_ptr<HeadlessContext> HeadlessContext::create(const ContextOptions& options) {
  std::unique_ptr<HeadlessContext> ctx(new HeadlessContext());
  auto get_platform_display =
      egl_proc<PFNEGLGETPLATFORMDISPLAYEXTPROC>("eglGetPlatformDisplayEXT");
  if (!get_platform_display)
    throw UserError("EGL: eglGetPlatformDisplayEXT is missing; libglvnd's EGL is required");

  EGLDisplay display = EGL_NO_DISPLAY;
  std::string platform_name;
  if (options.platform != EglPlatform::Surfaceless) {
    if (EGLDeviceEXT device = find_nvidia_device()) {
      display = get_platform_display(EGL_PLATFORM_DEVICE_EXT, device, nullptr);
      platform_name = "device";
    } else if (options.platform == EglPlatform::Device) {
      throw UserError("EGL: --egl-platform device asked for, but no NVIDIA EGL device was found");
    }
  }
  if (display == EGL_NO_DISPLAY) {
    display = get_platform_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
    platform_name = "surfaceless";
  }
  if (display == EGL_NO_DISPLAY)
    throw UserError("EGL: no display on the device or surfaceless platform (" +
                    egl_error_string(eglGetError()) + ")");
  EGLint major = 0, minor = 0;
  if (!eglInitialize(display, &major, &minor))
    throw UserError("EGL: eglInitialize failed on the " + platform_name + " platform (" +
                    egl_error_string(eglGetError()) + ")");
  ctx->display_ = display;
  const char* egl_vendor = eglQueryString(display, EGL_VENDOR);

  if (!eglBindAPI(EGL_OPENGL_API)) throw UserError("EGL: this display offers no desktop OpenGL");

  std::vector<EGLint> attributes = {EGL_CONTEXT_MAJOR_VERSION, 4,
                                    EGL_CONTEXT_MINOR_VERSION, 5,
                                    EGL_CONTEXT_OPENGL_PROFILE_MASK,
                                    EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT};
  if (options.debug_output) {
    attributes.push_back(EGL_CONTEXT_OPENGL_DEBUG);
    attributes.push_back(EGL_TRUE);
  }
  attributes.push_back(EGL_NONE);
  // EGL_KHR_no_config_context and EGL_KHR_surfaceless_context: no surface is ever made.
  EGLContext context = eglCreateContext(display, EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT,
                                        attributes.data());
  if (context == EGL_NO_CONTEXT) {
    // Say what the device does offer, so the user knows why it is refused.
    const EGLint plain[] = {EGL_NONE};
    EGLContext fallback = eglCreateContext(display, EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT, plain);
    std::string found = "no OpenGL context at all";
    if (fallback != EGL_NO_CONTEXT &&
        eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, fallback)) {
      const char* version = reinterpret_cast<const char*>(glGetString(GL_VERSION));
      const char* renderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
      found = std::string("OpenGL ") + (version ? version : "?") + " on " +
              (renderer ? renderer : "?");
      eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
      eglDestroyContext(display, fallback);
    }
    eglTerminate(display);
    ctx->display_ = nullptr;
    throw UserError("ldmbench needs an OpenGL 4.5 core context; the " + platform_name +
                    " EGL platform gave " + found);
  }
  ctx->context_ = context;
  if (!eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, context))
    throw UserError("EGL: eglMakeCurrent without a surface failed (" +
                    egl_error_string(eglGetError()) + ")");

  ctx->device_ = describe_current_context(platform_name, options.debug_output);
  ctx->device_.egl_vendor = egl_vendor ? egl_vendor : "";
  return ctx;
}

DeviceInfo describe_current_context(const std::string& platform_name, bool debug_output) {
  DeviceInfo info;
  info.egl_platform = platform_name;
  auto gl_string = [](GLenum name) {
    const char* s = reinterpret_cast<const char*>(glGetString(name));
    return std::string(s ? s : "");
  };
  info.gl_renderer = gl_string(GL_RENDERER);
  info.gl_vendor = gl_string(GL_VENDOR);
  info.gl_version = gl_string(GL_VERSION);
  info.glsl_version = gl_string(GL_SHADING_LANGUAGE_VERSION);
  GLint value = 0;
  glGetIntegerv(GL_MAJOR_VERSION, &value);
  info.gl_major = value;
  glGetIntegerv(GL_MINOR_VERSION, &value);
  info.gl_minor = value;
  if (info.gl_major * 10 + info.gl_minor < 45)
    throw UserError("ldmbench needs OpenGL 4.5 core; found " + info.gl_version + " on " +
                    info.gl_renderer);
  GLint64 block = 0;
  glGetInteger64v(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &block);
  info.max_ssbo_block_bytes = block;
  glGetIntegerv(GL_MAX_SHADER_STORAGE_BUFFER_BINDINGS, &value);
  info.max_ssbo_bindings = value;
  info.has_int64_atomics = has_gl_extension("GL_NV_shader_atomic_int64");
  GLint timer_bits = 0;
  glGetQueryiv(GL_TIMESTAMP, GL_QUERY_COUNTER_BITS, &timer_bits);
  info.has_timer_queries = timer_bits > 0;
  if (debug_output) {
    glEnable(GL_DEBUG_OUTPUT);
    glEnable(GL_DEBUG_OUTPUT_SYNCHRONOUS);
    glDebugMessageCallback(debug_callback, nullptr);
    info.debug_output = true;
  }
  // The self-tests of behaviour the structures rely on (once per driver and process).
  try {
    info.driver_defects = driver_conformance().defects_text();
  } catch (const GpuError& e) {
    info.driver_defects = std::string("self-test could not run: ") + e.what();
  }
  return info;
}

bool has_gl_extension(const std::string& name) {
  GLint count = 0;
  glGetIntegerv(GL_NUM_EXTENSIONS, &count);
  for (GLint i = 0; i < count; ++i) {
    const char* ext = reinterpret_cast<const char*>(glGetStringi(GL_EXTENSIONS, GLuint(i)));
    if (ext && name == ext) return true;
  }
  return false;
}

bool HeadlessContext::has_extension(const std::string& name) const {
  return has_gl_extension(name);
}

HeadlessContext::~HeadlessContext() {
  if (display_) {
    eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    if (context_) eglDestroyContext(display_, context_);
    eglTerminate(display_);
  }
}

}  // namespace ldm
