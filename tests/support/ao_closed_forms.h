#pragma once
// Closed forms of the AO of the analytic scenes (harness/scene/analytic_scenes.cpp), derived
// below and each checked against an independent quadrature in tests/reference/
// ao_analytic_test.cpp; the reference renderer and the peers (tests/peers) are tested against
// them.
#include <cmath>
#include <numbers>

namespace ldm::test {

// Floor point under an infinite parallel ceiling at height h, V = min(d/d_max, 1)^p.
// With u = cos(theta) (pdf 2u for cosine-weighted directions) the ceiling is at d = h/u, so
// V = 1 for u < c = h/d_max and V = (c/u)^p above:
//   AO = c^2 + ∫_c^1 2u (c/u)^p du = c^2 + 2 c^p (1 - c^(2-p)) / (2 - p)   (p != 2)
//                                  = c^2 (1 + 2 ln(1/c))                   (p = 2).
inline double parallel_planes_ao(double h, double d_max, double p) {
  const double c = h / d_max;
  if (c >= 1.0) return 1.0;
  if (p == 2.0) return c * c * (1.0 + 2.0 * std::log(1.0 / c));
  return c * c + 2.0 * std::pow(c, p) * (1.0 - std::pow(c, 2.0 - p)) / (2.0 - p);
}

// Floor point at distance a from an infinite vertical wall, V = min(d/d_max, 1)^2, κ = a/d_max.
// With s = sin(theta) and the azimuth φ measured from the direction to the wall, the pdf is
// s ds dφ / π and the wall is hit at d = a / (s cos φ) (cos φ > 0). For k = κ / cos φ < 1 the
// inner integral is ∫_0^k s ds + ∫_k^1 s k²/s² ds = k² (1/2 - ln k), else 1/2. Integrating
// over φ with ∫ sec² = tan and ∫ sec² ln cos = tan ln cos + tan - φ, φ0 = arccos κ:
//   AO = 1/2 + (1/π) [3κ sqrt(1 - κ²) - 2κ² arccos κ + π/2 - arccos κ]   (κ < 1), else 1.
inline double wall_ao(double a, double d_max) {
  constexpr double kPi = std::numbers::pi;
  const double k = a / d_max;
  if (k >= 1.0) return 1.0;
  return 0.5 + (3.0 * k * std::sqrt(1.0 - k * k) - 2.0 * k * k * std::acos(k) + kPi / 2.0 -
                std::acos(k)) /
                   kPi;
}

// Form factor from a differential area to a parallel rectangle a x b at height h with one
// corner straight above it, A = a/h, B = b/h: the fraction of cosine-weighted rays that hit it.
inline double corner_form_factor(double A, double B) {
  constexpr double kPi = std::numbers::pi;
  const double sa = std::sqrt(1.0 + A * A), sb = std::sqrt(1.0 + B * B);
  return (A / sa * std::atan(B / sa) + B / sb * std::atan(A / sb)) / (2.0 * kPi);
}

// Unattenuated AO under a square ceiling of half-size W at height h, floor point (px, pz):
// the square is four rectangles, each with a corner above the point.
inline double square_ceiling_ao(double px, double pz, double W, double h) {
  double occluded = 0.0;
  for (double sx : {-1.0, 1.0})
    for (double sz : {-1.0, 1.0})
      occluded += corner_form_factor((W + sx * px) / h, (W + sz * pz) / h);
  return 1.0 - occluded;
}

}  // namespace ldm::test
