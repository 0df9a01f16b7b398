#pragma once
// The ambient occlusion pass of thesis §4.4 over any structure, through its query API.
#include "harness/gl/gl_objects.h"
#include "harness/image/image.h"
#include "harness/measure/gpu_timer.h"
#include "harness/passes/gbuffer_pass.h"
#include "harness/passes/trace_steps.h"
#include "harness/scene/scene.h"
#include "ldm_impls/ldm_structure.h"

namespace ldm {

class AoPass {
 public:
  AoPass(const LdmStructure& structure, const BuildInputs& in, int width, int height,
         const AoSettings& settings);
  void render(const GBufferPass& gbuffer, GpuTimer* timer);
  Image read_image() const;  // one channel, linear, top row first
  // The trace's loop iterations over every frame rendered so far.
  TraceStepCounts trace_steps() const { return steps_.read(); }

 private:
  void compile();
  const LdmStructure& structure_;
  const GpuViewSet& views_;
  int width_, height_;
  AoSettings settings_;
  GlTexture2D output_;
  GlFramebuffer framebuffer_;
  GlVertexArray empty_vao_;
  GlProgram program_;
  TraceStepCounter steps_;
  uint64_t generation_ = 0;  // the structure's storage_generation() program_ was built for
};

}  // namespace ldm
