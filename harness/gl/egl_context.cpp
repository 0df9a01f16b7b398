#include "harness/gl/egl_context.h"

#include <EGL/egl.h>
#include <EGL/eglext.h>

#include <algorithm>
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

std::vector<EGLDeviceEXT> egl_devices() {
  auto query_devices = egl_proc<PFNEGLQUERYDEVICESEXTPROC>("eglQueryDevicesEXT");
  if (!query_devices) return {};
  EGLint count = 0;
  if (!query_devices(0, nullptr, &count) || count <= 0) return {};
  std::vector<EGLDeviceEXT> devices(static_cast<size_t>(count));
  if (!query_devices(count, devices.data(), &count)) return {};
  devices.resize(static_cast<size_t>(std::max<EGLint>(count, 0)));
  return devices;
}

const char* device_extensions(EGLDeviceEXT device) {
  auto query_string = egl_proc<PFNEGLQUERYDEVICESTRINGEXTPROC>("eglQueryDeviceStringEXT");
  return query_string ? query_string(device, EGL_EXTENSIONS) : nullptr;
}

// What the device's extensions say it is (no context made).
EglDeviceSummary summarize(EGLDeviceEXT device, int index) {
  EglDeviceSummary summary;
  summary.index = index;
  const char* extensions = device_extensions(device);
  auto query_string = egl_proc<PFNEGLQUERYDEVICESTRINGEXTPROC>("eglQueryDeviceStringEXT");
  auto query_attrib = egl_proc<PFNEGLQUERYDEVICEATTRIBEXTPROC>("eglQueryDeviceAttribEXT");
  if (contains_word(extensions, "EGL_NV_device_cuda") && query_attrib) {
    EGLAttrib ordinal = -1;
    if (query_attrib(device, EGL_CUDA_DEVICE_NV, &ordinal) && ordinal >= 0)
      summary.cuda_ordinal = int(ordinal);
  }
  if (contains_word(extensions, "EGL_EXT_device_drm") && query_string)
    if (const char* node = query_string(device, EGL_DRM_DEVICE_FILE_EXT)) summary.drm_node = node;
  summary.software = contains_word(extensions, "EGL_MESA_device_software");
  return summary;
}

// The UUID of EGL_EXT_device_persistent_id, or "".
std::string egl_device_uuid(EGLDeviceEXT device) {
  using QueryBinary = EGLBoolean (*)(EGLDeviceEXT, EGLint, EGLint, void*, EGLint*);
  auto query_binary = egl_proc<QueryBinary>("eglQueryDeviceBinaryEXT");
  if (!query_binary || !contains_word(device_extensions(device), "EGL_EXT_device_persistent_id"))
    return "";
  unsigned char uuid[16] = {};
  EGLint size = 0;
  if (!query_binary(device, EGL_DEVICE_UUID_EXT, sizeof uuid, uuid, &size) || size != 16) return "";
  return format_uuid(uuid);
}

// GL_DEVICE_UUID_EXT of the current context (GL_EXT_memory_object), or "".
std::string gl_device_uuid() {
  using GetUnsignedBytei = void (*)(GLenum, GLuint, GLubyte*);
  auto get = egl_proc<GetUnsignedBytei>("glGetUnsignedBytei_vEXT");
  if (!get || !has_gl_extension("GL_EXT_memory_object")) return "";
  unsigned char uuid[16] = {};
  for (int i = 0; i < 16 && glGetError() != GL_NO_ERROR; ++i) {  // errors of earlier calls
  }
  get(0x9597 /* GL_DEVICE_UUID_EXT */, 0, uuid);
  if (glGetError() != GL_NO_ERROR) return "";
  return format_uuid(uuid);
}

// What the current context says of its device; a context made on the surfaceless platform
// (or by a window system) runs Mesa's default driver: software when the renderer is Mesa's.
DeviceIdentity gl_device_identity(const DeviceInfo& info) {
  DeviceIdentity identity;
  identity.renderer = info.gl_renderer;
  const std::string& driver = info.gl_driver;
  identity.software = driver == "llvmpipe" || driver == "softpipe" ||
                      (driver == "zink" && info.gl_renderer.find("llvmpipe") != std::string::npos);
  identity.gl_uuid = gl_device_uuid();
  return identity;
}

std::vector<EGLint> context_attributes(bool debug_output) {
  std::vector<EGLint> attributes = {EGL_CONTEXT_MAJOR_VERSION, 4,
                                    EGL_CONTEXT_MINOR_VERSION, 5,
                                    EGL_CONTEXT_OPENGL_PROFILE_MASK,
                                    EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT};
  if (debug_output) {
    attributes.push_back(EGL_CONTEXT_OPENGL_DEBUG);
    attributes.push_back(EGL_TRUE);
  }
  attributes.push_back(EGL_NONE);
  return attributes;
}

// Tries an OpenGL 4.5 core context on the device; its GL_RENDERER, or nullopt when none is
// made. Leaves nothing current and nothing initialised.
std::optional<std::string> try_context(EGLDeviceEXT device) {
  auto get_platform_display = egl_proc<PFNEGLGETPLATFORMDISPLAYEXTPROC>("eglGetPlatformDisplayEXT");
  if (!get_platform_display) return std::nullopt;
  EGLDisplay display = get_platform_display(EGL_PLATFORM_DEVICE_EXT, device, nullptr);
  EGLint major = 0, minor = 0;
  if (display == EGL_NO_DISPLAY || !eglInitialize(display, &major, &minor)) return std::nullopt;
  std::optional<std::string> renderer;
  const auto attributes = context_attributes(false);
  if (eglBindAPI(EGL_OPENGL_API)) {
    EGLContext context = eglCreateContext(display, EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT, attributes.data());
    if (context != EGL_NO_CONTEXT) {
      if (eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, context)) {
        const char* name = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
        renderer = name ? name : "";
        eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
      }
      eglDestroyContext(display, context);
    }
  }
  eglTerminate(display);
  return renderer;
}

void APIENTRY debug_callback(GLenum source, GLenum type, GLuint id, GLenum severity, GLsizei,
                               const GLchar* message, const void*) {
  (void)source;
  if (severity == GL_DEBUG_SEVERITY_NOTIFICATION) return;
  std::fprintf(stderr, "[gl debug] type 0x%x id %u severity 0x%x: %s\n", type, id, severity,
               message);
}

}  // namespace

std::vector<EglDeviceSummary> list_egl_devices(bool try_contexts) {
  const std::vector<EGLDeviceEXT> devices = egl_devices();
  std::vector<EglDeviceSummary> summaries;
  for (size_t i = 0; i < devices.size(); ++i) {
    EglDeviceSummary summary = summarize(devices[i], int(i));
    if (try_contexts) {
      const auto renderer = try_context(devices[i]);
      summary.makes_context = renderer.has_value();
      summary.renderer = renderer.value_or("");
    }
    summaries.push_back(std::move(summary));
  }
  return summaries;
}

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

  // Which device (device_selection.h): described from the extensions, tried for a context
  // only where the choice is by position (no NVIDIA device).
  const std::vector<EGLDeviceEXT> devices =
      options.platform == EglPlatform::Surfaceless ? std::vector<EGLDeviceEXT>{} : egl_devices();
  std::vector<EglDeviceSummary> summaries;
  for (size_t i = 0; i < devices.size(); ++i) summaries.push_back(summarize(devices[i], int(i)));
  if (options.platform == EglPlatform::Surfaceless && options.gpu && options.gpu->source != "LDM_GPU")
    throw UserError(options.gpu->source + " " + std::to_string(options.gpu->n) +
                    ": a GPU is chosen on the EGL device platform, not with --egl-platform surfaceless");
  DeviceChoice choice{std::nullopt, "Mesa surfaceless platform (--egl-platform surfaceless)"};
  if (options.platform != EglPlatform::Surfaceless) {
    const bool prefer_surfaceless = options.platform == EglPlatform::Auto;
    if (device_choice_needs_context_probe(summaries, options.gpu, prefer_surfaceless))
      for (auto& summary : summaries) {
        const auto renderer = try_context(devices[size_t(summary.index)]);
        summary.makes_context = renderer.has_value();
        summary.renderer = renderer.value_or("");
      }
    if (summaries.empty() && options.platform == EglPlatform::Device)
      throw UserError("EGL: --egl-platform device asked for, but EGL lists no device");
    choice = choose_egl_device(summaries, options.gpu, prefer_surfaceless);
  }
  EGLDisplay display = EGL_NO_DISPLAY;
  std::string platform_name;
  const EglDeviceSummary* chosen = nullptr;
  if (choice.device_index) {
    chosen = &summaries[size_t(*choice.device_index)];
    display = get_platform_display(EGL_PLATFORM_DEVICE_EXT, devices[size_t(*choice.device_index)], nullptr);
    platform_name = "device";
  } else {
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

  const std::vector<EGLint> attributes = context_attributes(options.debug_output);
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
  if (chosen) {  // what EGL knows of the device adds to what GL says (describe_current_context)
    DeviceIdentity identity = gl_device_identity(ctx->device_);
    identity.software = chosen->software;
    identity.egl_uuid = egl_device_uuid(devices[size_t(chosen->index)]);
    identity.drm_node = chosen->drm_node;
    ctx->device_.device_id = device_id(identity);
  }
  ctx->device_.device_choice = choice.how;
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
  info.gl_driver = gl_driver_name(info.gl_renderer, info.gl_vendor, info.gl_version);
  info.device_id = device_id(gl_device_identity(info));
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
