#include "harness/passes/gtao_kernel.h"

#include <cmath>

#include "harness/gl/bindings.h"
#include "harness/gl/shader_program.h"

namespace ldm {

namespace {

ShaderDefines gtao_defines(const GtaoSettings& gtao, const AoSettings& ao) {
  ShaderDefines defines = binding_defines();
  defines.set("GTAO_SLICES", std::to_string(gtao.slices));
  defines.set("GTAO_STEPS", std::to_string(gtao.steps));
  // The reference's V weighs the rises where it is attenuated (unattenuated, W = 1 anyway).
  defines.set("GTAO_REFERENCE_WEIGHTS", ao.attenuated && gtao.reference_weights ? 1 : 0);
  defines.set("GTAO_NORMALIZED", gtao.normalized ? 1 : 0);
  return defines;
}

}  // namespace

GtaoKernel::GtaoKernel(const GtaoSettings& gtao, const AoSettings& ao, int width, int height)
    : FullscreenAoKernel("GTAO", "passes/gtao.frag", gtao_defines(gtao, ao), width, height) {
  program_.set("gtao_radius", gtao.radius_scale * ao.d_max);
  program_.set("gtao_d_max", ao.d_max);
  program_.set("gtao_falloff_exponent", ao.falloff_exponent);
  program_.set("gtao_falloff", gtao.falloff);
  program_.set("gtao_thickness", gtao.thickness);
  program_.set("gtao_step_power", gtao.step_power);
  program_.set("gtao_sin_bias", std::sin(kGtaoTangentBias));
  program_.set("gtao_jitter", gtao.jitter ? 1 : 0);
  check_gl("GTAO uniforms");
}

void GtaoKernel::set_camera(const GtaoCamera& camera) {
  program_.set("camera_eye", camera.eye.x, camera.eye.y, camera.eye.z);
  program_.set("camera_forward", camera.forward.x, camera.forward.y, camera.forward.z);
  program_.set("camera_right", camera.right.x, camera.right.y, camera.right.z);
  program_.set("camera_up", camera.up.x, camera.up.y, camera.up.z);
  program_.set("focal_pixels", camera.focal_pixels);
}

}  // namespace ldm
