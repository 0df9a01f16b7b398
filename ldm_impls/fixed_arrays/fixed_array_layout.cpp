#include "ldm_impls/fixed_arrays/fixed_array_layout.h"

#include <algorithm>

#include "harness/util/error.h"

namespace ldm {

uint32_t read_fixed_array_k(StructureParams& params) {
  return uint32_t(params.get_uint("k", 0, 0, 1u << 20));
}

FixedArrayLayout plan_fixed_arrays(const std::string& structure, uint32_t requested_k,
                                   const BuildInputs& in) {
  FixedArrayLayout layout;
  layout.pixels = in.views.views().total_pixels();
  layout.k_from_census = requested_k == 0;
  // An empty scene still gets one entry per pixel so that every buffer and index is valid.
  layout.k = layout.k_from_census ? std::max(1u, in.census.max_depth_complexity) : requested_k;
  const std::string what = "entries (k = " + std::to_string(layout.k) + " per pixel" +
                           (layout.k_from_census ? ", the census's maximum depth complexity" : "") +
                           "; a smaller k parameter loses fragments but fits)";
  if (layout.entries() >= (uint64_t(1) << 32))
    throw UserError(structure + ": " + std::to_string(layout.entries()) + " " + what +
                    " exceed what 32-bit entry indices address");
  checked_storage_block(structure, what, layout.entry_bytes());
  return layout;
}

ShaderDefines fixed_array_defines(const FixedArrayLayout& layout, const BuildInputs& in) {
  ShaderDefines defines = common_structure_defines(in);
  defines.set("FA_K", std::to_string(layout.k) + "u");
  return defines;
}

BuildStats fixed_array_stats(const GlBuffer& dropped_counter, uint64_t census_fragments) {
  uint32_t dropped = 0;
  dropped_counter.download(&dropped, sizeof dropped);
  BuildStats s;
  s.fragments_rasterized = census_fragments;
  s.fragments_lost = dropped;
  s.fragments_stored = census_fragments - std::min<uint64_t>(census_fragments, dropped);
  s.overflow = dropped > 0;  // k below some pixel's depth complexity: the build is lossy
  s.counters = {{"dropped_beyond_k", double(dropped)}};
  return s;
}

std::vector<std::pair<std::string, std::string>> fixed_array_sizing(
    const FixedArrayLayout& layout) {
  return {{"k", std::to_string(layout.k)},
          {"k_policy", layout.k_from_census ? "census_max_depth_complexity" : "parameter"},
          {"entries", std::to_string(layout.entries())},
          {"layout", "pixel-major"}};
}

}  // namespace ldm
