#pragma once
// The spot light's emission, shared by every renderer of the lighting passes: the Embree
// references (harness/reference/lighting_reference.h) and the GPU indirect pass, whose GLSL
// copy must compute exactly the same falloff.
//
// Radiant intensity toward the unit direction w leaving the light:
//   c       = dot(normalize(light.direction), w)            cosine of the angle off the axis
//   c_in    = cos(inner_angle_deg), c_out = cos(outer_angle_deg)   (c_in >= c_out)
//   falloff = smoothstep(c_out, c_in, c)  = t^2 (3 - 2t), t = clamp((c - c_out)/(c_in - c_out), 0, 1)
//             and, where the cone has no soft edge (c_in <= c_out, equal angles): c >= c_in ? 1 : 0
//             (GLSL's smoothstep is undefined for edge0 >= edge1: the GLSL copy must branch too)
//   I(w)    = light.intensity * falloff                      W/sr, linear RGB
// The falloff is smooth in cos(angle) (not in the angle), which is what makes the flux a
// closed form: with mu = cos(angle), dw = dmu dphi and ∫_0^1 t^2 (3 - 2t) dt = 1/2,
//   Φ = ∫_S² I(w) dw = 2π I [(1 - c_in) + (c_in - c_out)/2] = 2π I [1 - (c_in + c_out)/2].
#include <glm/glm.hpp>

#include "harness/scene/scene.h"

namespace ldm {

// falloff(c) above, for the cosine c of the angle between the light's axis and a direction.
float spot_falloff(const SpotLight& light, float cos_angle);
// I(w) in W/sr (RGB) toward the unit vector `direction_from_light`.
glm::vec3 spot_radiant_intensity(const SpotLight& light, const glm::vec3& direction_from_light);
// ∫_S² falloff(w) dw in steradians: the solid angle the light would fill at full intensity.
// Φ = intensity * this.
float spot_effective_solid_angle(const SpotLight& light);
// The solid angle of the outer cone, 2π (1 - c_out): where I(w) > 0 (the region a primary
// photon must be emitted into).
float spot_outer_cone_solid_angle(const SpotLight& light);
// The light's total radiant flux Φ = ∫ I(w) dw in W (RGB), closed form above. A photon
// emitted into solid angle dw around w carries I(w) dw of it (thesis §5.4.1 splits Φ
// equally among n_e photons, which is the same for a uniform cone).
glm::vec3 spot_radiant_flux(const SpotLight& light);

// Photon bookkeeping for a light rendered as a pinhole camera (thesis §5.1.4, §5.4.1): an
// image plane at distance 1 along the axis, half-extent t = tan(outer angle) (a frustum
// whose inscribed circle is the outer cone; outer < 90°), R × R texels. The texel whose
// centre has normalised coordinates (x, y) in [-1, 1]² sees the solid angle
//   dω = (2t/R)² / (1 + (xt)² + (yt)²)^(3/2),
// and a photon through it carries I(ω) dω of the flux: summed over the texels this tends to
// Φ as R grows (tests/reference/lighting_reference_test.cpp), whatever the falloff, whereas
// Φ / n_e per photon holds only for a cone of uniform intensity.
float spot_texel_solid_angle(float tan_half_extent, int resolution, float x_ndc, float y_ndc);

}  // namespace ldm
