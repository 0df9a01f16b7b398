// Splatting (thesis §5.4.2): one photon on a plane deposits exactly its flux, E_p * A over
// the footprint, and only inside its footprint's ellipse.
#include <gtest/gtest.h>

#include <cmath>

#include "indirect/indirect_support.h"

namespace ldm {
namespace {

// A plane seen straight down, one photon splatted by the pass's splatting stage alone.
struct OnePhoton {
  test::IndirectRun run;
  Image radiance, positions, albedo;
  OnePhoton(const StoredPhoton& photon, std::map<std::string, std::string> params)
      : run(plane_scene(), "psppsll", 2, 32, 160, std::move(params)) {
    auto& lighting = const_cast<PhotonLighting&>(run.lighting());
    lighting.splat_photons(run.pass->camera_gbuffer(), {photon});
    radiance = lighting.read_indirect();
    positions = run.pass->camera_gbuffer().read_positions();
    albedo = run.pass->camera_gbuffer().read_albedo();
  }
  static Scene plane_scene() {
    Scene scene = load_scene("plane");
    scene.camera.eye = {0.0f, 1.5f, 0.0f};
    return scene;
  }
  // The irradiance the splat put on the plane, integrated: sum of pi L / rho times each
  // pixel's area on the plane (from the G-buffer's neighbouring positions).
  glm::dvec3 deposited_flux() const {
    glm::dvec3 total(0.0);
    for (int y = 0; y + 1 < radiance.height; ++y)
      for (int x = 0; x + 1 < radiance.width; ++x) {
        auto p = [&](int i, int j) {
          return glm::dvec3(positions.at(i, j, 0), positions.at(i, j, 1), positions.at(i, j, 2));
        };
        const double area = glm::length(glm::cross(p(x + 1, y) - p(x, y), p(x, y + 1) - p(x, y)));
        for (int ch = 0; ch < 3; ++ch)
          total[ch] += M_PI * radiance.at(x, y, ch) / albedo.at(x, y, ch) * area;
      }
    return total;
  }
};

StoredPhoton photon_at(glm::vec3 position, glm::vec3 du, glm::vec3 dv, glm::vec3 flux) {
  StoredPhoton p{};
  p.position = position;
  p.normal = {0.0f, 1.0f, 0.0f};
  p.du_x = du;
  p.dv_x = dv;
  p.flux = flux;
  return p;
}

TEST(IndirectSplat, OnePhotonDepositsItsFlux) {
  // An anisotropic, sheared footprint, scaled by s = 2: the splat must still integrate to Phi.
  const StoredPhoton p = photon_at({0.05f, 0.0f, -0.03f}, {0.12f, 0.0f, 0.04f},
                                   {-0.03f, 0.0f, 0.09f}, {1.0f, 0.5f, 0.25f});
  const OnePhoton one(p, {{"s", "2"}});
  const glm::dvec3 flux = one.deposited_flux();
  for (int ch = 0; ch < 3; ++ch) EXPECT_NEAR(flux[ch], p.flux[ch], 0.01 * p.flux[ch]) << ch;
}

TEST(IndirectSplat, OnlyInsideTheFootprintEllipse) {
  const float s = 1.5f;
  const StoredPhoton p = photon_at({0.0f, 0.0f, 0.0f}, {0.2f, 0.0f, 0.0f}, {0.05f, 0.0f, 0.1f},
                                   {1.0f, 1.0f, 1.0f});
  const OnePhoton one(p, {{"s", "1.5"}});
  // Filter coordinates of a plane point: y = x - x_p = (alpha Du + beta Dv) s / 2 inside the
  // ellipse iff alpha^2 + beta^2 < 1.
  const glm::dvec3 du = glm::dvec3(p.du_x) * double(s), dv = glm::dvec3(p.dv_x) * double(s);
  const double det = du.x * dv.z - du.z * dv.x;
  int inside = 0, lit_inside = 0;
  double peak = 0;
  for (int y = 0; y < one.radiance.height; ++y)
    for (int x = 0; x < one.radiance.width; ++x) {
      const double px = one.positions.at(x, y, 0), pz = one.positions.at(x, y, 2);
      const double alpha = 2.0 * (px * dv.z - pz * dv.x) / det;
      const double beta = 2.0 * (du.x * pz - du.z * px) / det;
      const double l2 = alpha * alpha + beta * beta;
      const float value = one.radiance.at(x, y, 0);
      if (l2 >= 1.0) ASSERT_EQ(value, 0.0f) << "outside the footprint at " << x << "," << y;
      if (l2 < 0.9) {
        ++inside;
        lit_inside += value > 0.0f;
      }
      // Silverman's kernel 3/pi (1 - l^2)^2 times E = Phi / (pi/4 |s Du x s Dv|) times rho.
      const double expected = l2 < 1.0 ? 0.5 * (3.0 / M_PI) * (1 - l2) * (1 - l2) / (M_PI / 4 * std::abs(det)) : 0.0;
      if (l2 < 0.98) ASSERT_NEAR(value, expected, 1e-3 * expected + 1e-6) << x << "," << y;
      peak = std::max(peak, double(value));
    }
  EXPECT_GT(inside, 100);
  EXPECT_EQ(lit_inside, inside);
  EXPECT_GT(peak, 0.0);
}

// The topological bias: a receiving point off the photon's tangent plane by h sees the kernel
// at l = a h / r (r = sqrt(|s Du x s Dv|) / 2), so a photon lifted off the plane by more than
// r / a deposits nothing, and a = 0 ignores the lift.
TEST(IndirectSplat, TopologicalBiasCutsPointsOffThePlane) {
  const glm::vec3 du(0.2f, 0.0f, 0.0f), dv(0.0f, 0.0f, 0.2f);  // r = 0.1 at s = 1
  const StoredPhoton lifted = photon_at({0.0f, 0.15f, 0.0f}, du, dv, {1.0f, 1.0f, 1.0f});
  const OnePhoton biased(lifted, {{"s", "1"}, {"a", "1"}});
  double sum = 0;
  for (float v : biased.radiance.pixels) sum += v;
  EXPECT_EQ(sum, 0.0);
  const OnePhoton unbiased(lifted, {{"s", "1"}, {"a", "0"}});
  const glm::dvec3 flux = unbiased.deposited_flux();
  EXPECT_GT(flux.x, 0.5);  // the quad, lifted, projects larger: most of it still lands
}

}  // namespace
}  // namespace ldm
