#pragma once
// What PPFLA and PSPPFLA (thesis §3.2.6, §3.2.7) share: k depth entries for every LDM pixel
// of every view, pixel-major (entry i of pixel p at p * k + i, the layout of §3.2.6), all
// views in one buffer like PSPPSLL (§3.4.4), and a counter of the fragments that did not fit.
//
// k follows the sizing policy (ldm_impls/common/sizing.h): the deepest pixel the policy
// knows of (oracle: the census's; census: this frame's census; previous_frame: the last
// build's own counts, or the first guess's fragments per pixel), so the arrays model exactly
// what the scene requires; under budget, the largest k the budget holds. An explicit `k`
// parameter overrides the policy. A smaller k than a pixel's depth makes the build lossy
// (each dropped fragment counted on the GPU); a larger one only costs memory.
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "harness/gl/gl_objects.h"
#include "ldm_impls/ldm_structure.h"

namespace ldm {

struct FixedArrayLayout {
  uint64_t pixels = 0;  // N * R_LDM^2
  uint32_t k = 0;       // entries per pixel
  std::string k_source;  // size_source(): the policy's name or "parameter"
  uint64_t entries() const { return pixels * k; }
  uint64_t entry_bytes() const { return entries() * sizeof(uint32_t); }
};

// Reads the `k` parameter: 0 (the default) means "as the sizing policy says".
AxisSpec fixed_array_k_parameter();
uint32_t read_fixed_array_k(const StructureParams& params);

// k for `needs`: the deepest pixel when known, else the fragments per pixel rounded up; >= 1.
uint32_t k_for(const SizingNeeds& needs, uint64_t pixels);

// Chooses k (the parameter, else the budget less `fixed_bytes`, else k_for(plan's needs))
// and checks that the entries fit one storage block and 32-bit indices; throws UserError
// naming k otherwise.
FixedArrayLayout plan_fixed_arrays(const std::string& structure, uint32_t requested_k,
                                   const BuildInputs& in, uint64_t fixed_bytes);
// The same layout with another k (a resize), checked the same way.
FixedArrayLayout resized_fixed_arrays(const std::string& structure, FixedArrayLayout layout,
                                      uint32_t k);

// common_structure_defines plus FA_K (k as a GLSL uint literal).
ShaderDefines fixed_array_defines(const FixedArrayLayout& layout);

// Read-back of the dropped-fragment counter.
uint32_t read_dropped(const GlBuffer& dropped_counter);

// BuildStats from what the build rasterised (the structure's own count) and dropped.
BuildStats fixed_array_stats(uint64_t rasterized, uint64_t dropped);

std::vector<std::pair<std::string, std::string>> fixed_array_sizing(const FixedArrayLayout& layout);

}  // namespace ldm
