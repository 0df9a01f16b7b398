#pragma once
// The frame HBAO and GTAO share: the camera's G-buffer, the pass's AO kernel over it
// (HbaoKernel, GtaoKernel: run(positions, normals) into an R32F target()), then optionally
// the separable cross-bilateral smoothing of that AO (HbaoBlur: HBAO's blur, GTAO's
// denoise). Drawn, timed, read back, scored and counted alike; each pass keeps its kernel's
// settings and its records' names.
#include <cstdint>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "harness/metrics/ao_range.h"
#include "harness/passes/gbuffer_pass.h"
#include "harness/passes/hbao_kernel.h"
#include "harness/passes/pass.h"
#include "harness/scene/camera.h"

namespace ldm {

template <typename Kernel>
class ScreenSpaceAo {
 public:
  // `name`: the kernel's sub-pass and its targets' prefix ("hbao"); `smoothing`: the
  // smoothing's sub-pass ("blur").
  ScreenSpaceAo(std::string name, std::string smoothing)
      : name_(std::move(name)), smoothing_(std::move(smoothing)) {}

  // The G-buffer, `kernel` (its camera set by the caller) and, with a radius, the smoothing.
  void prepare(const PassInputs& in, std::unique_ptr<Kernel> kernel, uint32_t smoothing_radius) {
    scene_ = &in.scene;
    gpu_scene_ = &in.gpu_scene;
    width_ = in.width;
    height_ = in.height;
    gbuffer_ = std::make_unique<GBufferPass>(in.width, in.height);
    kernel_ = std::move(kernel);
    smoothing_blur_.reset();
    if (smoothing_radius > 0) {
      smoothing_blur_ = std::make_unique<HbaoBlur>(smoothing_radius, kernel_->target());
      smoothing_blur_->set_camera(smoothing_camera(in));
    }
  }

  // The camera of the smoothing (and of HBAO's kernel): eye, forward and the focal length
  // in pixels.
  static HbaoCamera smoothing_camera(const PassInputs& in) {
    const CameraFrame frame = camera_frame(in.scene.camera, in.width, in.height);
    return {frame.eye, frame.forward, 0.5f * float(in.height) / frame.tan_half_fov_y};
  }

  void render(GpuTimer* timer) const {
    gbuffer_->render(*gpu_scene_, *scene_, timer);
    {
      ScopedSubpass timed(timer, name_);
      kernel_->run(gbuffer_->positions(), gbuffer_->normals());
    }
    if (smoothing_blur_) {
      ScopedSubpass timed(timer, smoothing_);
      smoothing_blur_->run(gbuffer_->positions(), gbuffer_->normals());
    }
  }

  std::vector<PassImage> images() const {
    return {{"ao", image_from_gl_rows(kernel_->target().read_floats(1), width_, height_, 1)}};
  }

  // Render targets, every texel written each frame (allocated = used). The G-buffer is
  // counted too: the LDM AO draws the same one, but its records count only its structure.
  std::vector<BufferMemory> memory() const {
    std::vector<BufferMemory> targets = gbuffer_->memory();
    const uint64_t ao_bytes = kernel_->target().bytes();
    targets.push_back({name_ + "_ao", ao_bytes, ao_bytes});
    if (smoothing_blur_) {
      const uint64_t scratch = smoothing_blur_->scratch().bytes();
      targets.push_back({name_ + "_" + smoothing_ + "_scratch", scratch, scratch});
    }
    return targets;
  }

  Image coverage() const { return coverage_mask(gbuffer_->read_positions()); }

  std::vector<std::pair<std::string, RecordValue>> results() const {
    return ao_range_results(images().front().image, gbuffer_->read_positions());
  }

  Kernel& kernel() const { return *kernel_; }

 private:
  std::string name_, smoothing_;
  const Scene* scene_ = nullptr;
  const GpuScene* gpu_scene_ = nullptr;
  int width_ = 0, height_ = 0;
  // GL objects, created by prepare(): a pass is also constructed without a GL context
  // (argument checks, `ldmbench passes`).
  std::unique_ptr<GBufferPass> gbuffer_;
  std::unique_ptr<Kernel> kernel_;
  std::unique_ptr<HbaoBlur> smoothing_blur_;  // null without smoothing
};

}  // namespace ldm
