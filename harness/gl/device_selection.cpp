#include "harness/gl/device_selection.h"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <cstdlib>

#include "harness/util/error.h"

namespace ldm {
namespace {

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return s;
}

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

std::optional<int> parse_index(const std::string& text) {
  if (text.empty() || text.size() > 6) return std::nullopt;
  for (char c : text)
    if (!std::isdigit(static_cast<unsigned char>(c))) return std::nullopt;
  return std::stoi(text);
}

std::string device_list(const std::vector<EglDeviceSummary>& devices) {
  if (devices.empty()) return "EGL lists no device (`ldmbench info`)";
  std::string out = "the EGL devices (`ldmbench info`):";
  for (const auto& d : devices) out += "\n  " + d.describe();
  return out;
}

bool any_cuda(const std::vector<EglDeviceSummary>& devices) {
  return std::any_of(devices.begin(), devices.end(),
                     [](const EglDeviceSummary& d) { return d.cuda_ordinal.has_value(); });
}

}  // namespace

std::string EglDeviceSummary::kind() const {
  if (cuda_ordinal) return "cuda " + std::to_string(*cuda_ordinal);
  if (!drm_node.empty()) return "drm " + drm_node;
  if (software) return "software";
  return "other";
}

std::string EglDeviceSummary::describe() const {
  std::string out = std::to_string(index) + ": " + kind() + ", ";
  out += renderer.empty() ? (makes_context ? "context made" : "no OpenGL 4.5 core context") : renderer;
  return out;
}

std::optional<GpuRequest> parse_gpu_request(const std::optional<std::string>& option,
                                            const std::optional<std::string>& environment,
                                            const std::string& option_name) {
  if (option) {
    if (auto n = parse_index(*option)) return GpuRequest{*n, option_name};
    throw UserError(option_name + " '" + *option + "': expected a GPU index, a non-negative integer "
                    "(on NVIDIA the CUDA ordinal, 0 the first GPU CUDA_VISIBLE_DEVICES leaves visible)");
  }
  if (environment && !environment->empty()) {
    if (auto n = parse_index(*environment)) return GpuRequest{*n, "LDM_GPU"};
    throw UserError("LDM_GPU='" + *environment + "': expected a GPU index, a non-negative integer "
                    "(on NVIDIA the CUDA ordinal, 0 the first GPU CUDA_VISIBLE_DEVICES leaves visible)");
  }
  return std::nullopt;
}

bool device_choice_needs_context_probe(const std::vector<EglDeviceSummary>& devices,
                                       const std::optional<GpuRequest>& request,
                                       bool prefer_surfaceless) {
  if (devices.empty() || any_cuda(devices)) return false;
  return request.has_value() || !prefer_surfaceless;
}

DeviceChoice choose_egl_device(const std::vector<EglDeviceSummary>& devices,
                               const std::optional<GpuRequest>& request, bool prefer_surfaceless) {
  const int n = request ? request->n : 0;
  const std::string source = request ? request->source : std::string("default");
  const std::string asked = request ? request->source + " " + std::to_string(n) : "the default device";
  if (any_cuda(devices)) {
    for (const auto& d : devices)
      if (d.cuda_ordinal == n) return {d.index, "CUDA ordinal " + std::to_string(n) + " (" + source + ")"};
    throw UserError(asked + ": no NVIDIA device has CUDA ordinal " + std::to_string(n) +
                    " (ordinals count the GPUs CUDA_VISIBLE_DEVICES leaves visible); " +
                    device_list(devices));
  }
  if (!request && prefer_surfaceless) return {std::nullopt, "Mesa surfaceless platform (default)"};
  std::vector<const EglDeviceSummary*> usable;
  for (const auto& d : devices)
    if (d.makes_context) usable.push_back(&d);
  if (n < int(usable.size()))
    return {usable[size_t(n)]->index, "device " + std::to_string(n) + " of " +
                                          std::to_string(usable.size()) +
                                          " that make a context (" + source + ")"};
  throw UserError(asked + ": " +
                  (usable.empty() ? std::string("no EGL device makes an OpenGL 4.5 core context")
                                  : "out of range: " + std::to_string(usable.size()) +
                                        " EGL device(s) make an OpenGL 4.5 core context, "
                                        "numbered from 0") +
                  "; " + device_list(devices));
}

std::string gl_driver_name(const std::string& renderer, const std::string& vendor,
                           const std::string& version) {
  const std::string r = lower(renderer), v = lower(vendor);
  // zink names the driver under it in parentheses: "zink (llvmpipe (LLVM 15 ...))".
  if (r.rfind("zink", 0) == 0) return "zink";
  for (const char* mesa : {"llvmpipe", "softpipe", "virgl", "swr"})
    if (r.rfind(mesa, 0) == 0) return mesa;
  if (contains(v, "nvidia")) return "nvidia";
  const bool is_mesa = contains(lower(version), "mesa");
  if (is_mesa) {
    if (contains(r, "radeonsi") || contains(v, "amd")) return "radeonsi";
    if (contains(v, "intel")) return "iris";
    if (contains(r, "nv") || contains(v, "nouveau")) return "nouveau";
    if (contains(r, "d3d12")) return "d3d12";
    return "mesa";
  }
  if (v.rfind("ati ", 0) == 0 || contains(v, "amd") || contains(v, "advanced micro devices")) return "amd";
  if (v.empty()) return "unknown";
  std::string name;
  for (char c : v) name += std::isalnum(static_cast<unsigned char>(c)) ? c : '_';
  return name;
}

std::optional<GpuRequest> gpu_request_from_environment(const std::optional<std::string>& option,
                                                       const std::string& option_name) {
  const char* variable = std::getenv("LDM_GPU");
  return parse_gpu_request(option, variable ? std::optional<std::string>(variable) : std::nullopt,
                           option_name);
}

std::string device_id(const DeviceIdentity& d) {
  // A software device's UUID names the Mesa release, not a device ("mesa22.3.6" in ASCII,
  // the same for llvmpipe and lavapipe): its renderer says more.
  if (d.software) return "software:" + d.renderer;
  if (!d.egl_uuid.empty()) return d.egl_uuid;
  if (!d.gl_uuid.empty()) return d.gl_uuid;
  if (!d.drm_node.empty()) return d.drm_node;
  return "unknown:" + d.renderer;
}

std::string format_uuid(const unsigned char (&bytes)[16]) {
  char text[37];
  std::snprintf(text, sizeof text,
                "%02x%02x%02x%02x-%02x%02x-%02x%02x-%02x%02x-%02x%02x%02x%02x%02x%02x", bytes[0],
                bytes[1], bytes[2], bytes[3], bytes[4], bytes[5], bytes[6], bytes[7], bytes[8],
                bytes[9], bytes[10], bytes[11], bytes[12], bytes[13], bytes[14], bytes[15]);
  return text;
}

}  // namespace ldm
