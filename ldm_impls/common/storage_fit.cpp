#include "ldm_impls/common/storage_fit.h"

#include <cmath>
#include <cstdio>

namespace ldm {
namespace {

// The N * R^2 rule is an estimate (fragments of a scene are not exactly proportional to the
// pixels): keep a margin below the limit.
constexpr double kMargin = 0.95;

std::string percent(double share) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3g%%", 100.0 * share);
  return text;
}

}  // namespace

std::string storage_fit_suggestion(const StorageBlockExceeded& e, const FragmentCensus& census,
                                   uint32_t views, uint32_t resolution) {
  if (e.bytes == 0 || e.limit == 0) return {};
  const double scale = double(e.limit) / double(e.bytes) * kMargin;
  const auto n_fit = uint32_t(std::floor(double(views) * scale));
  const auto r_fit = uint32_t(std::floor(double(resolution) * std::sqrt(scale)));
  std::string options;
  auto add = [&](const std::string& option) { options += (options.empty() ? "" : ", or ") + option; };
  if (n_fit >= 1) add("N = " + std::to_string(n_fit) + " (at R_LDM " + std::to_string(resolution) + ")");
  if (r_fit >= 1) add("R_LDM = " + std::to_string(r_fit) + " (at N " + std::to_string(views) + ")");
  if (e.entries_per_pixel > 0) {
    // A fixed array's bytes are k entries per pixel: exactly proportional to k.
    const auto k_fit = uint32_t(std::floor(double(e.entries_per_pixel) * double(e.limit) / double(e.bytes)));
    if (k_fit >= 1) {
      const DepthProfile profile = depth_profile(census);
      add("k = " + std::to_string(k_fit) + " (--param " + e.structure + ":k=" + std::to_string(k_fit) +
          "; lossy: " + percent(profile.share_above(k_fit)) + " of the occupied LDM pixels hold more, " +
          std::to_string(census.fragments_beyond(k_fit)) + " of " + std::to_string(census.total_fragments) +
          " fragments would be dropped)");
    }
  }
  if (options.empty()) return {};
  return "; from this scene's census (" + std::to_string(census.total_fragments) +
         " fragments, deepest pixel " + std::to_string(census.max_depth_complexity) +
         ") the storage grows about as N x R_LDM^2, so about " + options + " would fit";
}

UserError explained_refusal(const StorageBlockExceeded& e, const FragmentCensus& census,
                            uint32_t views, uint32_t resolution) {
  return UserError(std::string(e.what()) + storage_fit_suggestion(e, census, views, resolution));
}

}  // namespace ldm
