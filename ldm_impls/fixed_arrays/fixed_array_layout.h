#pragma once
// What PPFLA and PSPPFLA (thesis §3.2.6, §3.2.7) share: k depth entries for every LDM pixel
// of every view, pixel-major (entry i of pixel p at p * k + i, the layout of §3.2.6), all
// views in one buffer like PSPPSLL (§3.4.4), and a counter of the fragments that did not fit.
//
// k defaults to the census's maximum depth complexity: the smallest k that loses nothing, so
// the arrays model exactly what the scene requires. A smaller k makes the build lossy (each
// dropped fragment counted on the GPU); a larger one only costs memory.
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
  bool k_from_census = true;
  uint64_t entries() const { return pixels * k; }
  uint64_t entry_bytes() const { return entries() * sizeof(uint32_t); }
};

// Reads the `k` parameter: 0 (the default) means "the census's maximum depth complexity".
uint32_t read_fixed_array_k(StructureParams& params);

// Chooses k and checks that the entries fit one storage block and 32-bit indices; throws
// UserError naming k otherwise.
FixedArrayLayout plan_fixed_arrays(const std::string& structure, uint32_t requested_k,
                                   const BuildInputs& in);

// common_structure_defines plus FA_K (k as a GLSL uint literal).
ShaderDefines fixed_array_defines(const FixedArrayLayout& layout, const BuildInputs& in);

// The dropped-fragment counter, read back into BuildStats: fragments_rasterized is the census
// total (the same geometry pass, so the same fragments), stored = rasterized - dropped.
BuildStats fixed_array_stats(const GlBuffer& dropped_counter, uint64_t census_fragments);

std::vector<std::pair<std::string, std::string>> fixed_array_sizing(const FixedArrayLayout& layout);

}  // namespace ldm
