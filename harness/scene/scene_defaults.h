#pragma once
// Settings a scene does not give, derived from its size. A mesh file knows nothing of a
// camera, a light or an AO distance, and fixed defaults (an eye 5 units from the origin,
// d_max = 1) are meaningless for a model in millimetres or kilometres: an engine of radius
// 418 mm got an AO range of 0.2% of its size and a constant reference. So where a scene
// does not set them, they follow its bounding sphere (centre C, radius R):
//
//   camera  looks at C from the direction kCameraDirection, at the distance where the
//           sphere fills the field of view (fov_y 40 degrees, 5% margin);
//   light   a spot at C + R * kLightOffset aimed at C, its cone just wider than the sphere
//           seen from there, its intensity d^2 W/sr at distance d, so that the irradiance at
//           C is 1 W/m^2 at any scale;
//   d_max   kDerivedDMaxFraction * R.
//
// What is already relative needs nothing: the normal offset is in LDM pixels, and the
// indirect pass's settings are per light texel (s, a) or in LDM pixels (depth threshold),
// or off (T_foot). Each derived setting's source is recorded in the scene (and the record).
#include <string>

#include "harness/scene/scene.h"

namespace ldm {

inline constexpr float kDerivedDMaxFraction = 0.2f;
inline constexpr float kDerivedFovYDeg = 40.0f;
inline constexpr float kDerivedFramingMargin = 1.05f;
inline const glm::vec3 kCameraDirection{0.55f, 0.45f, 1.0f};  // from C towards the eye
inline const glm::vec3 kLightOffset{0.35f, 2.0f, 0.25f};     // from C, in units of R

// Which of `scene`'s settings its source gave: the rest are derived from its bounding
// sphere and their sources set to "derived (...)".
struct GivenSettings {
  bool camera = false, light = false, d_max = false;
};
void derive_size_defaults(Scene& scene, const GivenSettings& given);

// Every source as `source`, for a scene whose settings all come from one place
// ("generator cornell", "scene file").
void set_setting_sources(Scene& scene, const std::string& source);

}  // namespace ldm
