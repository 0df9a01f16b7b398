#pragma once
// The counting replay's totals of the LDM geometry pass, counted by additive blending instead
// of atomics (issue 33: what counting adds to a run).
//
// A counting site in a fragment shader is an atomic per fragment; llvmpipe runs each as a loop
// over its SIMD lanes, 15-19 ns per fragment and site, which made a counted build 2-9 times the
// measured one. A fragment's outputs cost next to nothing, so in the counting replay a
// construction shader's totals (work_add) become channels of 32-bit float targets that the
// draw blends additively (shaders/common/work_counters.glsl, WORK_BLEND_TARGETS), and a compute
// pass sums each target into the running sub-pass's counters after the draw
// (shaders/ldm/common/blended_work_sum.comp). The storage the shader writes is the same; the
// replay's check compares its lists with the measured frames' as for every replay.
//
// Exactness: a pixel's blended sum is exact while it stays below 2^24 (every value added is a
// non-negative integer, so the sum only grows: a pixel below the limit at the end never
// passed it). The sum reports the largest pixel value to the counting scope
// (WorkCountingScope::report_inexact_blend) when it reached the limit, and the replay is run
// again with atomics. Distributions (work_sample) keep their atomics.
#include <cstdint>
#include <string>
#include <vector>

#include "harness/gl/gl_objects.h"
#include "harness/gl/shader_program.h"

namespace ldm {

// The totals a fragment shader counts by blending: its work_add sites' names, one channel
// each (channel i is component i % 4 of target i / 4).
struct BlendedTotals {
  std::vector<std::string> names;
  int targets() const { return int((names.size() + 3) / 4); }
  bool empty() const { return names.empty(); }
};

// The totals `fragment_file` (preprocessed with `defines` and the counting replay's) adds
// with work_add, where the counting replay declares them. Empty (count with atomics) outside
// a counting scope that blends (WorkCountingScope::blending_totals), where the shader's main()
// does not start with LDM_SKIP_HELPER_INVOCATIONS (which zeroes the outputs), where it adds
// more totals than the device's draw buffers hold, or where the targets at this resolution
// would pass kMaxBlendedTargetBytes.
BlendedTotals blended_totals_of(const std::string& fragment_file, const ShaderDefines& defines,
                                uint32_t resolution);
inline constexpr uint64_t kMaxBlendedTargetBytes = uint64_t(64) << 20;

// The defines that make a fragment stage count `totals` by blending.
ShaderDefines blend_defines(const BlendedTotals& totals);

// The pixel value up to which a blended sum is exact: 2^24, or less where the environment's
// LDM_WORK_BLEND_EXACT_LIMIT says so (the tests of the fallback to atomics).
uint32_t blended_exact_limit();

// The targets of one program's blended totals, the framebuffer that holds them and the
// program that sums them. Built in the counting scope (the sum is a counting variant).
class BlendedWorkTargets {
 public:
  BlendedWorkTargets(uint32_t resolution, BlendedTotals totals);
  // Binds the framebuffer of the targets, cleared, with additive blending on.
  void begin() const;
  // Turns blending off and adds every target's channels to the running sub-pass's counters;
  // a pixel that reached blended_exact_limit() is reported to the counting scope.
  void end_and_sum() const;

 private:
  uint32_t resolution_;
  BlendedTotals totals_;
  std::vector<GlTexture2D> targets_;
  GlFramebuffer framebuffer_;
  GlProgram sum_program_;
  mutable GlBuffer largest_;  // the largest pixel value of the last sum
};

}  // namespace ldm
