#pragma once
// What would fit when a structure's storage exceeds the device's storage block
// (GL_MAX_SHADER_STORAGE_BLOCK_SIZE; 128 MiB on llvmpipe): the N, R_LDM or (for a fixed
// array) k that would, estimated from the refused configuration's own census. Every
// structure's storage grows about as N * R_LDM^2 (the pixels, and the fragments of surfaces,
// both do), and a fixed array's also as k; the census says what a smaller k would lose.
#include <cstdint>
#include <string>

#include "ldm_impls/common/fragment_census.h"
#include "ldm_impls/ldm_structure.h"

namespace ldm {

// A sentence to append to the refusal ("; from this scene's census: ..."), or "" when
// nothing of this configuration would fit.
std::string storage_fit_suggestion(const StorageBlockExceeded& refusal, const FragmentCensus& census,
                                   uint32_t views, uint32_t resolution);

// The refusal with the suggestion appended, as a UserError (what a failed record says).
UserError explained_refusal(const StorageBlockExceeded& refusal, const FragmentCensus& census,
                            uint32_t views, uint32_t resolution);

}  // namespace ldm
