// The AO reference against closed forms (derived in the comments, each formula also checked
// by an independent numerical quadrature), on the analytic built-in scenes.
//
// Tolerances come from the sample count: V lies in [0, 1], so Var(V) <= E[V](1 - E[V]) and a
// pixel mean of n samples has standard error <= sqrt(AO (1 - AO) / n). Each pixel must lie
// within 5 of those of the closed form, and the mean deviation over all pixels within 5
// standard errors of the mean (this catches biases far below the per-pixel noise).
#include <cmath>
#include <functional>
#include <numbers>
#include <optional>

#include <gtest/gtest.h>

#include "harness/scene/camera.h"
#include "harness/reference/ao_estimator.h"
#include "harness/reference/ao_reference.h"
#include "harness/reference/embree_scene.h"
#include "harness/scene/generators.h"
#include "support/ao_closed_forms.h"
#include "support/ao_convergence.h"
#include "support/ao_reference_request.h"

namespace ldm {
namespace {

constexpr double kPiAo = std::numbers::pi;
constexpr int kSize = 64;
constexpr uint32_t kSppPerHalf = 512;

// The closed forms (parallel_planes_ao, wall_ao, corner_form_factor, square_ceiling_ao) are
// in tests/support/ao_closed_forms.h, shared with the peers' tests.
using test::corner_form_factor;
using test::parallel_planes_ao;
using test::square_ceiling_ao;
using test::wall_ao;

// ---- the closed forms against quadrature ----------------------------------------------------

TEST(AoClosedForms, ParallelPlanesMatchQuadrature) {
  for (double p : {1.0, 2.0, 3.0})
    for (double c : {0.1, 0.5, 0.9}) {
      const int n = 1000000;  // midpoint rule over u in (0, 1)
      double sum = 0.0;
      for (int i = 0; i < n; ++i) {
        const double u = (i + 0.5) / n;
        sum += 2.0 * u * std::pow(std::min(c / u, 1.0), p) / n;
      }
      EXPECT_NEAR(parallel_planes_ao(c, 1.0, p), sum, 1e-6) << "p " << p << " c " << c;
    }
}

TEST(AoClosedForms, WallMatchesQuadrature) {
  for (double k : {0.05, 0.3, 0.7, 0.95}) {
    const int ns = 2000, nphi = 4000;  // midpoint rule over s in (0, 1), φ in (-π, π)
    double sum = 0.0;
    for (int j = 0; j < nphi; ++j) {
      const double c = std::cos(-kPiAo + (j + 0.5) * 2.0 * kPiAo / nphi);
      for (int i = 0; i < ns; ++i) {
        const double s = (i + 0.5) / ns;
        const double v = c <= 0.0 ? 1.0 : std::pow(std::min(k / (s * c), 1.0), 2.0);
        sum += s * v;
      }
    }
    sum *= (1.0 / ns) * (2.0 * kPiAo / nphi) / kPiAo;
    EXPECT_NEAR(wall_ao(k, 1.0), sum, 1e-4) << "kappa " << k;
  }
}

TEST(AoClosedForms, SquareCeilingMatchesQuadrature) {
  // Rays at azimuth φ leave the square's shadow at the horizontal distance r(φ) from the
  // point to the square's edge, i.e. for sin²θ > r²/(r² + h²); the occluded fraction is
  // (1/2π) ∫ r²/(r² + h²) dφ (the pdf of s = sin θ being 2s ds).
  const double W = 1.5, h = 1.0;
  for (auto [px, pz] : {std::pair{0.0, 0.0}, std::pair{0.4, -0.3}, std::pair{-1.2, 1.4}}) {
    const int n = 200000;
    double occluded = 0.0;
    for (int j = 0; j < n; ++j) {
      const double phi = (j + 0.5) * 2.0 * kPiAo / n;
      const double dx = std::cos(phi), dz = std::sin(phi);
      const double rx = dx > 0 ? (W - px) / dx : dx < 0 ? (W + px) / -dx : INFINITY;
      const double rz = dz > 0 ? (W - pz) / dz : dz < 0 ? (W + pz) / -dz : INFINITY;
      const double r = std::min(rx, rz);
      occluded += r * r / (r * r + h * h) / n;
    }
    EXPECT_NEAR(square_ceiling_ao(px, pz, W, h), 1.0 - occluded, 1e-6);
  }
}

// ---- the renderer against the closed forms --------------------------------------------------

// Where pixel (x, y)'s primary ray meets the floor y = 0 (computed here, not by the renderer).
glm::dvec3 floor_point(const Scene& scene, int x, int y) {
  const CameraFrame camera = camera_frame(scene.camera, kSize, kSize);
  const glm::dvec3 d(camera.ray_direction(x, y, kSize, kSize));
  const glm::dvec3 eye(camera.eye);
  return eye + d * (-eye.y / d.y);
}

float ray_offset(const Scene& scene) {
  const Scene centred = centred_on_bounding_sphere(scene);  // EmbreeScene keeps a reference
  const EmbreeScene embree(centred);
  return AoEstimator(embree, scene.ao, kSize, kSize).ray_offset();
}

ReferenceResult render(const Scene& scene) {
  AoReferenceRequest request = test::ao_reference_request(kSize, kSppPerHalf);
  request.threads = 2;
  return render_ao_reference(scene, request);
}

// The reference's mean is held to float rounding of the stored mean (1e-6), over 9 in 10 pixels.
void expect_matches(const Image& image, uint32_t samples,
                    const std::function<std::optional<double>(int, int)>& expected) {
  test::expect_ao_converged(image, samples, {1e-6, 0.9}, expected);
}

TEST(AoReference, OpenPlaneIsFullyVisible) {
  for (bool attenuated : {true, false}) {
    Scene scene = generate_scene("plane", nlohmann::json::object(), "test");
    scene.ao.attenuated = attenuated;
    const ReferenceResult r = render(scene);
    expect_matches(r.image, r.spp_total, [](int, int) { return 1.0; });
  }
}

TEST(AoReference, BackgroundIsZero) {
  Scene scene = generate_scene("plane", nlohmann::json::object(), "test");
  scene.camera.target = scene.camera.eye + glm::vec3(0, 1, 0);  // looking away from the plane
  const ReferenceResult r = render(scene);
  expect_matches(r.image, r.spp_total, [](int, int) { return 0.0; });
}

TEST(AoReference, ParallelPlanesMatchClosedForm) {
  // half_size 4 >= sqrt(d_max² - h²) (1.73) + the camera's footprint (0.52): every ray that
  // could reach d_max hits the ceiling, as under an infinite one.
  for (float falloff : {2.0f, 1.0f}) {
    Scene scene = generate_scene("parallel-planes", {{"h", 1.0}, {"d_max", 2.0}}, "test");
    scene.ao.falloff_exponent = falloff;
    // Secondary rays start ray_offset above the floor: the ceiling is that much closer.
    const double h = 1.0 - ray_offset(scene);
    const double ao = parallel_planes_ao(h, 2.0, falloff);
    const ReferenceResult r = render(scene);
    expect_matches(r.image, r.spp_total, [ao](int, int) { return ao; });
  }
}

TEST(AoReference, NormalFacesTheCameraAsInTheGBuffer) {
  // Seen from below, the floor's normal is flipped towards the camera: the hemisphere opens
  // downwards, away from the ceiling, and every ray escapes. Sampled around the unflipped
  // normal the pixels would show the parallel-planes value (about 0.6).
  Scene scene = generate_scene("parallel-planes", {{"h", 1.0}, {"d_max", 2.0}}, "test");
  scene.camera.eye = {0.0f, -0.5f, 0.0f};
  scene.camera.target = {0.0f, 0.0f, 0.0f};
  const ReferenceResult r = render(scene);
  expect_matches(r.image, r.spp_total, [](int, int) { return 1.0; });
}

TEST(AoReference, WallMatchesClosedForm) {
  // The camera sees the floor strip 0.04 < x < 1.16 next to the wall x = 0; rays within
  // d_max = 1 stay far inside the wall's 4 x 8 extent, so it acts as an infinite one.
  const Scene scene = generate_scene("wall", {{"d_max", 1.0}}, "test");
  const ReferenceResult r = render(scene);
  int near_wall = 0;
  expect_matches(r.image, r.spp_total, [&](int x, int y) {
    const double a = floor_point(scene, x, y).x;  // the distance to the wall
    near_wall += a < 0.5;
    return wall_ao(a, 1.0);
  });
  EXPECT_GT(near_wall, kSize * kSize / 4);  // the interesting part is in view
}

TEST(AoReference, SquareCeilingMatchesFormFactor) {
  const double W = 1.5;
  const Scene scene = generate_scene(
      "parallel-planes", {{"h", 1.0}, {"half_size", W}, {"attenuated", false}}, "test");
  const double h = 1.0 - ray_offset(scene);
  const ReferenceResult r = render(scene);
  expect_matches(r.image, r.spp_total, [&](int x, int y) {
    const glm::dvec3 p = floor_point(scene, x, y);
    return square_ceiling_ao(p.x, p.z, W, h);
  });
}

}  // namespace
}  // namespace ldm
