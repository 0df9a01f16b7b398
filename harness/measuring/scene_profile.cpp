#include "harness/measuring/scene_profile.h"

#include <cstdio>
#include <optional>

#include "harness/measuring/accuracy.h"
#include "harness/records/harness_columns.h"
#include "harness/views/view_set.h"

namespace ldm {
namespace {

std::string format(const char* pattern, double value) {
  char buffer[256];
  std::snprintf(buffer, sizeof buffer, pattern, value);
  return buffer;
}

// The fixed arrays' k, from the structure's sizing columns (empty for other structures).
std::optional<uint32_t> fixed_array_k(const Measurement& m) {
  const std::string k = m.columns.text("sizing_k");
  if (k.empty()) return std::nullopt;
  return uint32_t(std::stoul(k));
}

}  // namespace

void add_scene_profile(Record& r, const Scene& scene, const Configuration& config,
                       const Measurement& m) {
  const BoundingSphere sphere = scene.bounding_sphere();
  r.set(columns::kSceneRadius, double(sphere.radius));
  r.set(columns::kCameraSource, scene.sources.camera);
  r.set(columns::kLightSource, scene.sources.light);
  r.set(columns::kDMaxSource, config.d_max ? std::string("run (--d-max)") : scene.sources.d_max);
  char offset[96];
  std::snprintf(offset, sizeof offset, "%.17g %.17g %.17g", scene.origin_offset.x,
                scene.origin_offset.y, scene.origin_offset.z);
  r.set(columns::kSceneOriginOffset, std::string(offset));
  r.set(columns::kFarFileVertices, scene.far_file_vertices);
  r.set(columns::kCollapsedTriangles, scene.collapsed_triangles);
  if (config.structure == kNoStructure) return;  // no census, no LDM pixels

  const DepthProfile& profile = m.depth_profile;
  r.set(columns::kDepthP50, profile.p50);
  r.set(columns::kDepthP90, profile.p90);
  r.set(columns::kDepthP99, profile.p99);
  r.set(columns::kDepthHistogram, profile.histogram_text());
  if (const auto k = fixed_array_k(m)) r.set(columns::kDepthShareAboveK, profile.share_above(*k));

  // The AO range in LDM pixels (the views' pixel, fitted to the bounding sphere).
  if (r.text("visibility") == "attenuated")
    if (const auto d_max = r.number("d_max")) {
      const double pixel = make_view_set(sphere, 1, config.resolution).views.front().pixel_size();
      r.set(columns::kDMaxLdmPixels, *d_max / pixel);
    }
}

void flag_degenerate_measurement(Record& r) {
  std::vector<std::string> reasons;
  for (const auto& [key, value] : r.fields()) {
    const std::string suffix = "ref_noise_mse";
    if (key.size() < suffix.size() || key.compare(key.size() - suffix.size(), suffix.size(), suffix) != 0)
      continue;
    const auto noise = r.number(key);
    if (noise && *noise == 0.0)
      reasons.push_back(key.substr(0, key.size() - suffix.size()) +
                        "reference without noise (" + key +
                        " = 0): every sample agreed, so it is a constant image (e.g. AO = 1 "
                        "wherever d_max reaches no occluder) and the error measures nothing");
  }
  if (const auto covered = r.number("covered_pixel_fraction"); covered && *covered == 0.0)
    reasons.push_back("the camera sees no surface: no pixel of the image is measured");
  if (const auto pixels = r.number("d_max_ldm_pixels"); pixels && *pixels < kMinAoRangeLdmPixels)
    reasons.push_back(format("d_max spans %.3g LDM pixels", *pixels) +
                      format(" (fewer than %g): the LDMs resolve the AO range in too few depth "
                             "samples; raise d_max or R_LDM", kMinAoRangeLdmPixels));
  std::string joined;
  for (const auto& reason : reasons) {
    joined += (joined.empty() ? "" : "; ") + reason;
    append_status_detail(r, "degenerate: " + reason);
  }
  r.set(columns::kDegenerate, joined);
}

}  // namespace ldm
