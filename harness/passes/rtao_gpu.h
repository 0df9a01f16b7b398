#pragma once
// Ray-traced ambient occlusion on the GPU: the reference's estimator (harness/reference/
// ao_estimator.h) at k rays per pixel, traced in a compute shader (shaders/passes/
// rtao_gpu.comp) through a BVH built once on the CPU by Embree's builder API
// (harness/passes/gpu_bvh.h) and uploaded to storage buffers. Its points and normals are the
// reference's own primary rays', traced on the GPU too (shaders/passes/rtao_gpu_primary.comp),
// or the rasterised G-buffer a hybrid renderer would use; its rays start where the
// reference's start, its directions and visibility are the reference's, and its random
// numbers are the CPU RTAO's for the same seed (shaders/passes/pcg32.glsl): where the CPU
// RTAO (`rtao`) is the ceiling and the cross-check, this is the GPU peer whose time stands
// beside every other GPU pass.
//
// Parameters (--param rtao_gpu:KEY=VALUE; comma lists are run axes, e.g. rtao_gpu:spp=1,4,16):
//   spp          rays per pixel k (1..65536, default 1)
//   seed         the random stream's seed (default 0x52544147, "RTAG"); its samples come from
//                pass kRtaoStreamPass of that seed, as the CPU RTAO's do (rtao.h), so they are
//                independent of the reference's halves, and rtao_gpu:seed=S draws exactly the
//                numbers rtao:seed=S draws
//   primary      trace (default: each pixel's primary ray through the BVH, the reference's
//                point exactly) | raster (the camera's rasterised G-buffer, as the screen-space
//                peers and the LDM AO have it; it differs from the reference's primary rays at
//                silhouettes, where the rasteriser snaps vertices to its sub-pixel grid)
//   d_max, visibility   as the LDM AO (also from --d-max / --visibility)
//
// Work: the shared counting replay (harness/measure/work_counters.h; work_counters()) counts
// the rays, the BVH nodes each ray visits and the triangles it tests: the record's
// work_rtao_gpu_* columns. Its own untimed replay on the measured instance (work(), the
// shaders compiled with RTAO_GPU_COUNT) stays for what must be judged there, also under
// --no-work: the loop iterations of each invocation, which llvmpipe's loop limiter judges
// (trace_steps.h; problems()), and that its image equals the measured frames' bit for bit.
// Records: rtao_gpu.cpp's columns() and work_counters().
#include <memory>
#include <optional>

#include "harness/passes/ao_pass_base.h"
#include "harness/passes/gbuffer_pass.h"
#include "harness/passes/gpu_bvh.h"
#include "harness/passes/pass.h"
#include "harness/records/columns.h"

namespace ldm {

// What one shader's counting replay found (per ray: over the rays it traced).
struct RayWork {
  uint64_t rays = 0;
  double nodes_mean = 0, triangles_mean = 0;
  uint64_t nodes_max = 0, triangles_max = 0;
  uint64_t steps_max = 0;    // loop iterations of the longest invocation
};

struct RtaoGpuWork {
  RayWork ao;                // the AO rays (every covered pixel's k)
  RayWork primary;           // the primary rays (one a pixel; none with primary=raster)
  uint32_t loop_limit = 0;   // the device's (shader_loop_iteration_limit), 0: none
  bool image_matches = true; // the replay's image equals the measured frames' bit for bit
};

// Pass's interface (LDM_PASS_DECLARATIONS) and what the pass adds: declarations alike in
// form in every pass's header, each its own.
class RtaoGpu : public AoPassBase {
 public:
  explicit RtaoGpu(StructureParams& params);
  ~RtaoGpu() override;
  LDM_PASS_DECLARATIONS("rtao_gpu");
  // What its shaders count in the shared counting replay (harness/measure/work_counters.h).
  static std::vector<WorkCounter> work_counters();
  // prepare() builds and uploads the BVH (once: the scene is static); it throws UserError
  // when a BVH array would exceed the device's storage block.
  Image coverage() const override;
  std::vector<std::string> problems() const override;
  std::vector<BufferMemory> memory() const override;

  const GpuBvh& bvh() const { return bvh_; }
  // The counting replay of the last render() (run once, on first use).
  const RtaoGpuWork& work() const;
  // The G-buffer the last render() traced or rasterised: each pixel's triangle (scene index
  // + 1, 0: background; GL rows, bottom first) and position (top row first).
  std::vector<uint32_t> read_triangle_ids() const;
  Image read_positions() const;

 private:
  GlProgram build(bool counting) const;
  GlProgram build_primary(bool counting) const;
  void bind_bvh() const;
  void trace_primary(const GlProgram& program) const;
  void trace_ao(const GlProgram& program, const GlTexture2D& target) const;
  void dispatch() const;
  const GlTexture2D& positions() const;
  const GlTexture2D& normals() const;
  const GlTexture2D& triangle_ids() const;

  uint32_t spp_ = 1;
  bool trace_primary_ = true;
  uint64_t seed_ = 0;
  AoSettings ao_;
  const Scene* scene_ = nullptr;
  const GpuScene* gpu_scene_ = nullptr;
  int width_ = 0, height_ = 0;
  GpuBvh bvh_;
  double upload_ms_ = 0;
  std::unique_ptr<GBufferPass> gbuffer_;  // primary=raster
  // primary=trace: the traced G-buffer (gbuffer.frag's targets and meaning).
  GlTexture2D traced_positions_, traced_normals_, traced_ids_;
  GlBuffer nodes_, triangles_, slots_;
  GlTexture2D ao_target_;
  GlProgram program_, primary_program_;
  mutable std::optional<RtaoGpuWork> work_;
};

}  // namespace ldm
