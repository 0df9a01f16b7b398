#pragma once
// Which EGL device a headless context opens (docs/guide/gpu-nodes.md#choosing-the-gpu): the
// mapping from the EGL devices found, `--gpu N` and `LDM_GPU=N` to one device, as pure
// functions over plain descriptions, so that multi-GPU nodes can be tested without one
// (tests/context/device_selection_test.cpp). egl_context.cpp describes the real devices and
// opens the one chosen; the driver naming (gl_driver column) lives here too.
#include <optional>
#include <string>
#include <vector>

namespace ldm {

// One EGL device as eglQueryDevicesEXT lists it.
struct EglDeviceSummary {
  int index = 0;                    // position in eglQueryDevicesEXT's list
  std::optional<int> cuda_ordinal;  // EGL_CUDA_DEVICE_NV (NVIDIA, EGL_NV_device_cuda)
  std::string drm_node;             // EGL_DRM_DEVICE_FILE_EXT (Mesa GPUs), else ""
  bool software = false;            // EGL_MESA_device_software (llvmpipe, zink on lavapipe)
  bool makes_context = false;       // an OpenGL 4.5 core context could be made on it
  std::string renderer;             // GL_RENDERER of that context, "" when none was made
  // "cuda 1", "drm /dev/dri/card0", "software" or "other": what the extensions say it is.
  std::string kind() const;
  // "0: cuda 1, NVIDIA A100-SXM4-80GB/PCIe/SSE2" (the line `ldmbench info` prints).
  std::string describe() const;
};

// Where N came from: --gpu (on the command line) or LDM_GPU (the environment).
struct GpuRequest {
  int n = 0;
  std::string source;  // "--gpu" (or gbench's --ldm_gpu) or "LDM_GPU"
};

// The request from the option's text (nullopt: not given) and the variable's (nullopt or
// empty: not set); the option wins. Throws UserError naming the option or variable when its
// value is not a non-negative integer.
// `option_name` is the option's spelling in errors and GpuRequest::source.
std::optional<GpuRequest> parse_gpu_request(const std::optional<std::string>& option,
                                            const std::optional<std::string>& environment,
                                            const std::string& option_name = "--gpu");

// parse_gpu_request(option, the LDM_GPU variable of this process).
std::optional<GpuRequest> gpu_request_from_environment(const std::optional<std::string>& option,
                                                       const std::string& option_name = "--gpu");

// The device to open: an index into the summaries, or none for Mesa's surfaceless platform.
struct DeviceChoice {
  std::optional<int> device_index;
  std::string how;  // "CUDA ordinal 0 (default)", "device 1 of 2 that make a context (--gpu)"
};

// The rules: when any device has a CUDA ordinal (NVIDIA), N is the process's CUDA ordinal
// (the N-th GPU CUDA_VISIBLE_DEVICES leaves visible), default 0, and other devices are not
// candidates. Otherwise N counts, in the list's order, the devices that make a context
// (`makes_context` must then be filled in); without a request and with `prefer_surfaceless`
// (the auto platform) no device is chosen, and Mesa's surfaceless platform opens its default
// driver as before. Throws UserError naming the request's source and listing the devices when
// N matches none, or when no device is found and one is required.
DeviceChoice choose_egl_device(const std::vector<EglDeviceSummary>& devices,
                               const std::optional<GpuRequest>& request, bool prefer_surfaceless);

// Whether choose_egl_device needs `makes_context` (no CUDA device and a device may be chosen
// by position): the caller then tries a context on every device first.
bool device_choice_needs_context_probe(const std::vector<EglDeviceSummary>& devices,
                                       const std::optional<GpuRequest>& request,
                                       bool prefer_surfaceless);

// The driver's short name from GL_RENDERER, GL_VENDOR and GL_VERSION: llvmpipe, softpipe,
// zink, nvidia, radeonsi, iris, ... ; for an unknown Mesa driver "mesa", else the vendor
// lower-cased (the gl_driver column).
std::string gl_driver_name(const std::string& renderer, const std::string& vendor,
                           const std::string& version);

// What names a device uniquely (the device_id column): a software device (llvmpipe, zink on
// lavapipe) "software:<renderer>"; else the UUID EGL gives (EGL_EXT_device_persistent_id),
// else the one GL gives (GL_EXT_memory_object's GL_DEVICE_UUID_EXT), else the DRM node, else
// "unknown:<renderer>".
struct DeviceIdentity {
  bool software = false;
  std::string egl_uuid, gl_uuid, drm_node, renderer;
};
std::string device_id(const DeviceIdentity& identity);

// A 16-byte UUID as 8-4-4-4-12 lower-case hex.
std::string format_uuid(const unsigned char (&bytes)[16]);

}  // namespace ldm
