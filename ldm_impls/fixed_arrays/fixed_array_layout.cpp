#include "ldm_impls/fixed_arrays/fixed_array_layout.h"
#include "ldm_impls/common/sizing_strategy.h"

#include <algorithm>

#include "harness/util/error.h"

namespace ldm {

AxisSpec fixed_array_k_parameter() {
  AxisSpec p = numeric_parameter(
      "k", AxisKind::UInt, 0, 1u << 20, "", "entries per pixel",
      "entries of every pixel's array; fragments beyond k are dropped and counted (lossy)");
  p.label = "k";
  p.default_note = "the deepest pixel, as the sizing policy knows it (0 too)";
  return p;
}

uint32_t read_fixed_array_k(const StructureParams& params) {
  return params.has("k") ? uint32_t(params.get_uint("k")) : 0;
}

uint32_t k_for(const SizingNeeds& needs, uint64_t pixels) {
  if (needs.max_depth_complexity > 0) return needs.max_depth_complexity;
  const uint64_t per_pixel = pixels ? (needs.fragments + pixels - 1) / pixels : 0;
  // An empty scene still gets one entry per pixel so that every buffer and index is valid.
  return uint32_t(std::clamp<uint64_t>(per_pixel, 1, 1u << 20));
}

namespace {
void check_layout(const std::string& structure, const FixedArrayLayout& layout) {
  const std::string what = "entries (k = " + std::to_string(layout.k) + " per pixel, from " +
                           layout.k_source + "; a smaller k parameter loses fragments but fits)";
  if (layout.entries() >= (uint64_t(1) << 32))
    throw UserError(structure + ": " + std::to_string(layout.entries()) + " " + what +
                    " exceed what 32-bit entry indices address");
  checked_storage_block(structure, what, layout.entry_bytes(), layout.k);
}
}  // namespace

FixedArrayLayout plan_fixed_arrays(const std::string& structure, uint32_t requested_k,
                                   const BuildInputs& in, uint64_t fixed_bytes) {
  FixedArrayLayout layout;
  layout.pixels = in.views.views().total_pixels();
  layout.k_source = size_source(in.sizing, requested_k != 0);
  if (requested_k != 0) {
    layout.k = requested_k;
  } else if (in.sizing.strategy().fixed_by_budget()) {
    const uint64_t k = budget_after(structure, in.sizing, fixed_bytes) /
                       (layout.pixels * sizeof(uint32_t));
    if (k == 0)
      throw UserError(structure + ": the sizing budget holds less than one entry per LDM pixel (" +
                      std::to_string(layout.pixels) + " pixels); raise --sizing-budget-mib");
    layout.k = uint32_t(std::min<uint64_t>(k, 1u << 20));
  } else {
    layout.k = k_for(in.sizing.initial, layout.pixels);
  }
  check_layout(structure, layout);
  return layout;
}

FixedArrayLayout resized_fixed_arrays(const std::string& structure, FixedArrayLayout layout,
                                      uint32_t k) {
  layout.k = k;
  check_layout(structure, layout);
  return layout;
}

ShaderDefines fixed_array_defines(const FixedArrayLayout& layout) {
  ShaderDefines defines = common_structure_defines(layout.pixels);
  defines.set("FA_K", std::to_string(layout.k) + "u");
  return defines;
}

uint32_t read_dropped(const GlBuffer& dropped_counter) {
  uint32_t dropped = 0;
  dropped_counter.download(&dropped, sizeof dropped);
  return dropped;
}

BuildStats fixed_array_stats(uint64_t rasterized, uint64_t dropped) {
  BuildStats s;
  s.fragments_rasterized = rasterized;
  s.fragments_lost = dropped;
  s.fragments_stored = rasterized - std::min(rasterized, dropped);
  s.overflow = dropped > 0;  // k below some pixel's depth complexity: the build is lossy
  s.counters = {{"dropped_beyond_k", double(dropped)}};
  return s;
}

std::vector<std::pair<std::string, std::string>> fixed_array_sizing(
    const FixedArrayLayout& layout) {
  return {{"k", std::to_string(layout.k)},
          {"k_source", layout.k_source},
          {"entries", std::to_string(layout.entries())},
          {"layout", "pixel-major"}};
}

}  // namespace ldm
