#pragma once
// Where the fragments of the LDM geometry passes come from. Every construction pass (and the
// census) is a fragment shader that includes shaders/ldm/ldm_fragment.glsl for its pixel,
// depth and view; a structure compiles it with build_program() and runs it with run(), never
// naming the source, so the same shaders can be fed:
//   RasterFragmentSource     the scene rasterised into every LDM view (ldm_rasterizer.h):
//                            what ldmbench measures
//   SyntheticFragmentSource  a given list of (pixel, depth) run by a compute shader, many
//                            invocations per pixel at once (synthetic_fragments.h): the
//                            contention tests of the lock-free insertions
#include <string>

#include "harness/gl/driver_probe.h"
#include "harness/gl/gl_objects.h"
#include "harness/gl/shader_program.h"

namespace ldm {

class FragmentSource {
 public:
  virtual ~FragmentSource() = default;
  // A program that runs `fragment_file` (from shaders/) on this source's fragments, with the
  // binding defines and `defines`.
  virtual GlProgram build_program(const std::string& fragment_file,
                                  const ShaderDefines& defines) const = 0;
  // Runs `program` (from build_program()) once per fragment; ends with a storage and
  // atomic-counter barrier so later passes see every write.
  virtual void run(const GlProgram& program) const = 0;
  // The shader stage the fragment shader runs in (a driver's defects can differ by stage:
  // harness/gl/driver_probe.h).
  virtual ProbeStage stage() const = 0;
};

}  // namespace ldm
