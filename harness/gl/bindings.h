#pragma once
// Binding points shared by the C++ side and the GLSL side (passed to shaders as defines, see
// binding_defines()). Structures own bindings 0-3; the harness owns the rest.
#include <cstdint>

#include "harness/gl/shader_program.h"

namespace ldm {

constexpr uint32_t kStructureBinding0 = 0;  // structure storage buffers: 0, 1, 2, 3
constexpr uint32_t kStructureCounterBinding = 0;  // atomic counter buffer binding
constexpr uint32_t kViewsBinding = 4;
constexpr uint32_t kCensusBinding = 5;
constexpr uint32_t kValidationBinding = 6;
constexpr uint32_t kPassBinding0 = 7;  // passes: 7, 8, ...
// The scene's per-triangle material index and material albedo (GpuScene::bind_materials),
// read by lighting passes' G-buffers: after the passes' first four.
constexpr uint32_t kMaterialsBinding = kPassBinding0 + 4;
constexpr uint32_t kMaterialAlbedoBinding = kPassBinding0 + 5;
// The synthetic fragment source (ldm_impls/common/synthetic_fragments.h) feeds construction
// passes, which never run together with a pass, so it borrows the passes' bindings.
constexpr uint32_t kSyntheticFragmentsBinding = kPassBinding0;
constexpr uint32_t kSyntheticRetryBinding = kPassBinding0 + 1;
// The inspector's per-block hashes (ldm_impls/common/ldm_inspector.h), beside the buffers a
// pass may still have bound (the trace-steps counters use kPassBinding0 + 6).
constexpr uint32_t kInspectBlocksBinding = kPassBinding0 + 7;
// The counting replay's work counters (harness/measure/work_counters.h): bound only there,
// beside everything a structure or pass binds.
constexpr uint32_t kWorkCountersBinding = kPassBinding0 + 8;
// The largest pixel of the counting replay's blended totals (ldm_impls/common/blended_work_counts.h).
constexpr uint32_t kBlendedLargestBinding = kPassBinding0 + 9;

ShaderDefines binding_defines();

}  // namespace ldm
