#pragma once
// Direction sampling around a surface normal.
#include <cmath>
#include <numbers>

#include <glm/glm.hpp>

namespace ldm {

// An orthonormal basis (t, b, n) around unit vector n, without branches or singularities
// (Duff et al., "Building an Orthonormal Basis, Revisited", JCGT 2017).
struct NormalFrame {
  glm::vec3 tangent, bitangent, normal;

  explicit NormalFrame(glm::vec3 n) : normal(n) {
    const float sign = std::copysign(1.0f, n.z);
    const float a = -1.0f / (sign + n.z);
    const float b = n.x * n.y * a;
    tangent = glm::vec3(1.0f + sign * n.x * n.x * a, sign * b, -sign * n.x);
    bitangent = glm::vec3(b, sign + n.y * n.y * a, -n.y);
  }
  glm::vec3 to_world(glm::vec3 local) const {
    return local.x * tangent + local.y * bitangent + local.z * normal;
  }
};

// Cosine-weighted direction in the local frame (z up), pdf cos(theta) / pi, from two uniform
// numbers in [0, 1) (Malley's method: a uniform point on the unit disk lifted to the
// hemisphere). z = sqrt(1 - u1) > 0 for u1 < 1, so the direction never lies in the surface.
inline glm::vec3 cosine_weighted_direction(float u1, float u2) {
  const float r = std::sqrt(u1);
  const float phi = 2.0f * std::numbers::pi_v<float> * u2;
  return {r * std::cos(phi), r * std::sin(phi), std::sqrt(1.0f - u1)};
}

}  // namespace ldm
