// Which EGL device --gpu / LDM_GPU selects (harness/gl/device_selection.h), over fake device
// lists: multi-GPU nodes, mixed drivers and bad requests without the hardware.
#include <gtest/gtest.h>

#include "harness/gl/device_selection.h"
#include "harness/util/error.h"

namespace ldm {
namespace {

// Device `index`, which names `renderer` where it makes a context (else no renderer).
EglDeviceSummary device(int index, bool makes_context, const std::string& renderer) {
  EglDeviceSummary d;
  d.index = index;
  d.makes_context = makes_context;
  d.renderer = makes_context ? renderer : "";
  return d;
}

EglDeviceSummary nvidia(int index, int ordinal) {
  EglDeviceSummary d = device(index, true, "NVIDIA A100-SXM4-80GB/PCIe/SSE2");
  d.cuda_ordinal = ordinal;
  return d;
}

EglDeviceSummary software(int index, bool makes_context = true) {
  EglDeviceSummary d = device(index, makes_context, "llvmpipe (LLVM 15.0.6, 256 bits)");
  d.software = true;
  return d;
}

EglDeviceSummary drm(int index, const std::string& node, bool makes_context) {
  EglDeviceSummary d = device(index, makes_context, "AMD Radeon RX 6800 (navi21, LLVM 15.0.6, DRM 3.49)");
  d.drm_node = node;
  return d;
}

std::optional<GpuRequest> gpu(int n, const std::string& source = "--gpu") { return GpuRequest{n, source}; }

std::string error_of(const std::vector<EglDeviceSummary>& devices, const std::optional<GpuRequest>& request,
                     bool prefer_surfaceless = true) {
  try {
    choose_egl_device(devices, request, prefer_surfaceless);
  } catch (const UserError& e) {
    return e.what();
  }
  return "";
}

// The NVIDIA driver lists its devices in an order of its own; N is the CUDA ordinal, so the
// task that Slurm gave GPU 3 (CUDA_VISIBLE_DEVICES=3: ordinal 0) opens exactly that one.
TEST(DeviceSelection, NvidiaDevicesAreChosenByCudaOrdinalNotByListPosition) {
  const std::vector<EglDeviceSummary> devices = {nvidia(0, 2), nvidia(1, 0), nvidia(2, 1), software(3)};
  EXPECT_EQ(choose_egl_device(devices, std::nullopt, true).device_index, 1);  // default: ordinal 0
  EXPECT_EQ(choose_egl_device(devices, gpu(0), true).device_index, 1);
  EXPECT_EQ(choose_egl_device(devices, gpu(1), true).device_index, 2);
  EXPECT_EQ(choose_egl_device(devices, gpu(2), true).device_index, 0);
  EXPECT_EQ(choose_egl_device(devices, gpu(2), true).how, "CUDA ordinal 2 (--gpu)");
  // The software device does not count among the GPUs: ordinal 3 does not exist.
  const std::string error = error_of(devices, gpu(3));
  EXPECT_NE(error.find("--gpu 3: no NVIDIA device has CUDA ordinal 3"), std::string::npos) << error;
  EXPECT_NE(error.find("0: cuda 2, NVIDIA A100"), std::string::npos) << error;
  EXPECT_NE(error.find("3: software, llvmpipe"), std::string::npos) << error;
  EXPECT_FALSE(device_choice_needs_context_probe(devices, gpu(1), true));  // no context tried
}

// Without NVIDIA, N counts the devices that make a context, in the list's order.
TEST(DeviceSelection, WithoutCudaNCountsTheDevicesThatMakeAContext) {
  const std::vector<EglDeviceSummary> devices = {drm(0, "/dev/dri/card0", false), software(1),
                                                 drm(2, "/dev/dri/card1", true), software(3, false)};
  EXPECT_TRUE(device_choice_needs_context_probe(devices, gpu(0), true));
  EXPECT_EQ(choose_egl_device(devices, gpu(0), true).device_index, 1);
  EXPECT_EQ(choose_egl_device(devices, gpu(1), true).device_index, 2);
  EXPECT_EQ(choose_egl_device(devices, gpu(1, "LDM_GPU"), true).how,
            "device 1 of 2 that make a context (LDM_GPU)");
  const std::string error = error_of(devices, gpu(2, "LDM_GPU"));
  EXPECT_NE(error.find("LDM_GPU 2: out of range: 2 EGL device(s) make"), std::string::npos) << error;
  for (const char* line : {"0: drm /dev/dri/card0, no OpenGL 4.5 core context", "1: software, llvmpipe",
                           "2: drm /dev/dri/card1, AMD Radeon", "3: software, no OpenGL"})
    EXPECT_NE(error.find(line), std::string::npos) << line << " in: " << error;
}

// The auto platform without a request keeps Mesa's surfaceless platform (its default
// driver, as before device selection); the device platform takes the first usable device.
TEST(DeviceSelection, WithoutRequestMesaKeepsSurfacelessUnlessTheDevicePlatformIsAsked) {
  const std::vector<EglDeviceSummary> devices = {software(0, false), software(1)};
  EXPECT_FALSE(choose_egl_device(devices, std::nullopt, true).device_index.has_value());
  EXPECT_FALSE(device_choice_needs_context_probe(devices, std::nullopt, true));
  EXPECT_EQ(choose_egl_device(devices, std::nullopt, false).device_index, 1);
  EXPECT_TRUE(device_choice_needs_context_probe(devices, std::nullopt, false));
}

TEST(DeviceSelection, NoDevicesIsSurfacelessByDefaultAndAClearErrorWhenOneIsAsked) {
  EXPECT_FALSE(choose_egl_device({}, std::nullopt, true).device_index.has_value());
  const std::string error = error_of({}, gpu(0));
  EXPECT_NE(error.find("--gpu 0: no EGL device makes an OpenGL 4.5 core context"), std::string::npos) << error;
  EXPECT_NE(error.find("EGL lists no device"), std::string::npos) << error;
  EXPECT_NE(error_of({}, std::nullopt, false).find("the default device"), std::string::npos);
}

TEST(DeviceSelection, TheOptionWinsOverTheVariableAndBadValuesNameTheirSource) {
  EXPECT_FALSE(parse_gpu_request(std::nullopt, std::nullopt).has_value());
  EXPECT_FALSE(parse_gpu_request(std::nullopt, std::string()).has_value());  // LDM_GPU= : unset
  auto r = parse_gpu_request(std::nullopt, std::string("3"));
  ASSERT_TRUE(r);
  EXPECT_EQ(r->n, 3);
  EXPECT_EQ(r->source, "LDM_GPU");
  r = parse_gpu_request(std::string("1"), std::string("3"));
  ASSERT_TRUE(r);
  EXPECT_EQ(r->n, 1);
  EXPECT_EQ(r->source, "--gpu");
  // The option wins even over a bad variable: the batch default does not break a command line.
  EXPECT_EQ(parse_gpu_request(std::string("0"), std::string("x"))->n, 0);
  for (const char* bad : {"-1", "x", "1.5", "", " 1", "0x1", "99999999"}) {
    EXPECT_THROW(parse_gpu_request(std::string(bad), std::nullopt), UserError) << bad;
    try {
      parse_gpu_request(std::nullopt, std::string(bad).empty() ? std::string("?") : std::string(bad));
      ADD_FAILURE() << "LDM_GPU=" << bad << " accepted";
    } catch (const UserError& e) {
      EXPECT_EQ(std::string(e.what()).rfind("LDM_GPU=", 0), 0u) << e.what();
    }
  }
  try {
    parse_gpu_request(std::string("two"), std::nullopt, "--ldm_gpu");
  } catch (const UserError& e) {
    EXPECT_EQ(std::string(e.what()).rfind("--ldm_gpu 'two'", 0), 0u) << e.what();
  }
}

TEST(DeviceSelection, DeviceKindsAndIds) {
  EXPECT_EQ(nvidia(0, 5).kind(), "cuda 5");
  EXPECT_EQ(drm(0, "/dev/dri/card2", true).kind(), "drm /dev/dri/card2");
  EXPECT_EQ(software(0).kind(), "software");
  EXPECT_EQ(EglDeviceSummary{}.kind(), "other");
  DeviceIdentity id;
  id.renderer = "llvmpipe (LLVM 15.0.6, 256 bits)";
  id.software = true;
  id.gl_uuid = "6d657361-3232-2e33-2e36-000000000000";  // Mesa's release, not a device
  EXPECT_EQ(device_id(id), "software:llvmpipe (LLVM 15.0.6, 256 bits)");
  id.software = false;
  id.drm_node = "/dev/dri/card0";
  EXPECT_EQ(device_id(id), id.gl_uuid);
  id.egl_uuid = "00112233-4455-6677-8899-aabbccddeeff";
  EXPECT_EQ(device_id(id), id.egl_uuid);  // EGL's persistent id first
  id.egl_uuid.clear();
  id.gl_uuid.clear();
  EXPECT_EQ(device_id(id), "/dev/dri/card0");
  id.drm_node.clear();
  EXPECT_EQ(device_id(id), "unknown:llvmpipe (LLVM 15.0.6, 256 bits)");
  const unsigned char bytes[16] = {0x6d, 0x65, 0x73, 0x61, 0x32, 0x32, 0x2e, 0x33, 0x2e, 0x36, 0, 0, 0, 0, 0, 0xff};
  EXPECT_EQ(format_uuid(bytes), "6d657361-3232-2e33-2e36-0000000000ff");
}

TEST(DeviceSelection, DriverNamesFromTheGlStrings) {
  EXPECT_EQ(gl_driver_name("llvmpipe (LLVM 15.0.6, 256 bits)", "Mesa/X.org", "4.5 (Core Profile) Mesa 22.3.6"), "llvmpipe");
  EXPECT_EQ(gl_driver_name("zink (llvmpipe (LLVM 15.0.6, 256 bits))", "Mesa/X.org", "4.6 (Core Profile) Mesa 22.3.6"), "zink");
  EXPECT_EQ(gl_driver_name("NVIDIA A100-SXM4-80GB/PCIe/SSE2", "NVIDIA Corporation", "4.6.0 NVIDIA 535.104.05"), "nvidia");
  EXPECT_EQ(gl_driver_name("AMD Radeon RX 6800 (navi21, LLVM 15.0.6, DRM 3.49, 6.1.0)", "AMD", "4.6 (Core Profile) Mesa 22.3.6"), "radeonsi");
  EXPECT_EQ(gl_driver_name("Mesa Intel(R) UHD Graphics 630 (CFL GT2)", "Intel", "4.6 (Core Profile) Mesa 22.3.6"), "iris");
  EXPECT_EQ(gl_driver_name("Intel(R) UHD Graphics", "Intel Corporation", "4.6.0 - Build 31.0"), "intel_corporation");
  EXPECT_EQ(gl_driver_name("AMD Radeon Pro", "ATI Technologies Inc.", "4.6.14761"), "amd");
}

}  // namespace
}  // namespace ldm
