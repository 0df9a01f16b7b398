// The photon tracing's bookkeeping (harness/passes/photon_lighting.h) and the direct light,
// against formulas computed here on the CPU from the pass's own light G-buffer, with the C++
// spot light of harness/scene/spot_light.h (so the GLSL copy is checked against it too).
#include <gtest/gtest.h>

#include <cmath>

#include "harness/scene/camera.h"
#include "harness/scene/spot_light.h"
#include "indirect/indirect_support.h"

namespace ldm {
namespace {

double flux_mean(glm::vec3 v) { return (double(v.x) + v.y + v.z) / 3.0; }

// What the pass's light G-buffer holds at GL texel (x, y) (row 0 at the bottom).
struct LightTexel {
  glm::vec4 position, normal, albedo;
};
LightTexel light_texel(const GBufferPass& g, const Image& pos, const Image& nrm,
                       const Image& alb, int x, int y) {
  const int row = g.height() - 1 - y;  // images are top row first
  auto at = [&](const Image& im) {
    return glm::vec4(im.at(x, row, 0), im.at(x, row, 1), im.at(x, row, 2), im.at(x, row, 3));
  };
  return {at(pos), at(nrm), at(alb)};
}

// The flux through light texel (x, y): I(d) times the texel's solid angle (its area on the
// image plane at distance 1 times cos^3 of its angle off the axis), as the pass defines it.
glm::vec3 texel_flux(const SpotLight& light, const CameraFrame& f, int x, int y, int r,
                     glm::vec3* d_hat_out) {
  const float u = (float(x) + 0.5f) / float(r) * 2.0f - 1.0f;
  const float v = (float(y) + 0.5f) / float(r) * 2.0f - 1.0f;
  const glm::vec3 d_hat = f.forward + f.tan_half_fov_y * (u * f.right + v * f.up);
  const float side = 2.0f * f.tan_half_fov_y / float(r);
  const float len = glm::length(d_hat);
  if (d_hat_out) *d_hat_out = d_hat;
  return spot_radiant_intensity(light, d_hat / len) * (side * side / (len * len * len));
}

// A closed diffuse sphere around the light (lightref's integrating sphere): every primary
// photon hits it, every secondary is traced to it. The stored flux of every photon, the
// flux emitted per texel and the primary flux per texel equal the formulas; the counts
// account for every secondary photon.
TEST(IndirectFlux, ClosedSphereBookkeeping) {
  const uint32_t n = 8;
  const int r_light = 32;
  const test::IndirectRun run(load_scene("closed-sphere"), "psppsll", n, 64, 64,
                              {{"r_light", std::to_string(r_light)}});
  const Scene& scene = run.setup->scene;
  const PhotonLighting& lighting = run.lighting();
  const PhotonCounts c = lighting.counts();

  // Every secondary photon is accounted for, and none was lost for want of space.
  EXPECT_EQ(c.emitted, c.escaped + c.culled_depth + c.culled_footprint + c.degenerate + c.appended);
  EXPECT_EQ(c.appended, c.stored + c.overflow);
  EXPECT_EQ(c.overflow, 0u);
  EXPECT_GT(c.stored, c.emitted / 10);
  // The hemisphere of every hit holds one of each +-forward pair: N secondaries per primary.
  EXPECT_EQ(c.emitted, (c.primary - c.primary_degenerate) * n);
  // Inside the closed sphere few escape: only directions whose hit the trace takes for the
  // traced point's own surface (nearly tangent ones).
  EXPECT_LT(double(c.escaped), 0.1 * double(c.emitted));

  const GBufferPass& g = lighting.light_gbuffer();
  const Image pos = g.read_positions(), nrm = g.read_normals(), alb = g.read_albedo();
  const CameraFrame frame = camera_frame(light_camera(scene.light), 1, 1);
  const auto tally = lighting.read_tally();
  const auto& views = run.setup->views.views;
  double primary_total = 0;
  uint64_t primaries = 0;
  std::vector<glm::vec3> phi1(size_t(r_light) * r_light, glm::vec3(0.0f));
  for (int y = 0; y < r_light; ++y)
    for (int x = 0; x < r_light; ++x) {
      const size_t i = size_t(y) * r_light + x;
      const LightTexel t = light_texel(g, pos, nrm, alb, x, y);
      const float u = (x + 0.5f) / r_light * 2 - 1, v = (y + 0.5f) / r_light * 2 - 1;
      const bool emits = u * u + v * v <= 1.0f && t.position.w != 0.0f;
      constexpr size_t K = PhotonLighting::kTallyEntries;
      ASSERT_EQ(tally[K * i].w, emits ? 1.0f : 0.0f) << "texel " << x << "," << y;
      if (!emits) continue;
      ++primaries;
      phi1[i] = texel_flux(scene.light, frame, x, y, r_light, nullptr);
      for (int ch = 0; ch < 3; ++ch)
        ASSERT_NEAR(tally[K * i][ch], phi1[i][ch], 1e-3 * phi1[i][ch] + 1e-12) << x << "," << y;
      primary_total += flux_mean(phi1[i]);
      // Flux into the secondaries: rho * Phi1 * 2/N * sum over the views of |cos|.
      double cos_sum = 0;
      for (const auto& view : views) cos_sum += std::abs(glm::dot(view.forward, glm::vec3(t.normal)));
      const glm::vec3 emitted = glm::vec3(t.albedo) * phi1[i] * float(2.0 * cos_sum / n);
      for (int ch = 0; ch < 3; ++ch)
        ASSERT_NEAR(tally[K * i + 1][ch], emitted[ch], 1e-3 * emitted[ch] + 1e-12);
    }
  EXPECT_EQ(primaries, c.primary);
  // The texels' flux is a midpoint quadrature of the spot's closed-form flux.
  EXPECT_NEAR(primary_total, flux_mean(spot_radiant_flux(scene.light)),
              0.01 * flux_mean(spot_radiant_flux(scene.light)));

  // Each stored photon: rho * Phi1 * 2 |cos(n1, forward_v)| / N of its texel and view, and
  // it went along the side of the view axis that lies in the hit's hemisphere.
  const auto photons = lighting.read_photons();
  ASSERT_EQ(photons.size(), c.stored);
  double stored_total = 0;
  for (const auto& p : photons) {
    const int x = int(p.light_texel % r_light), y = int(p.light_texel / r_light);
    const LightTexel t = light_texel(g, pos, nrm, alb, x, y);
    const auto& view = views.at(p.direction / 2);
    const float cos_o = glm::dot(view.forward, glm::vec3(t.normal));
    ASSERT_EQ(p.direction % 2 == 1, cos_o > 0.0f);
    const glm::vec3 expected = glm::vec3(t.albedo) * phi1[p.light_texel] * (2.0f * std::abs(cos_o) / n);
    // float rounding, amplified where the falloff's smoothstep is steep near the cone's edge
    for (int ch = 0; ch < 3; ++ch) ASSERT_NEAR(p.flux[ch], expected[ch], 1e-3 * expected[ch]);
    ASSERT_GT(glm::length(glm::cross(p.du_x, p.dv_x)), 0.0f);
    stored_total += flux_mean(p.flux);
  }
  // Reflected once, a closed sphere of albedo rho sends rho * Phi on (minus what escaped).
  const double rho = 0.5;
  EXPECT_LE(stored_total, rho * primary_total * 1.06);
}

// The direct image on an open plane (no shadow) is rho/pi * I(l) * cos / r^2 at every pixel,
// with I from the C++ spot light: the GLSL copy agrees with it across the whole falloff.
TEST(IndirectFlux, DirectLightMatchesTheCppSpot) {
  Scene scene = load_scene("plane");
  scene.camera.eye = {0.0f, 8.0f, 0.0f};  // sees the whole plane: the cone and its soft edge
  const test::IndirectRun run(scene, "psppsll", 2, 32, 96, {{"r_light", "64"}});
  const Scene& s = run.setup->scene;
  const Image direct = run.lighting().read_direct();
  const Image pos = run.pass->camera_gbuffer().read_positions();
  const Image nrm = run.pass->camera_gbuffer().read_normals();
  int lit = 0, soft = 0;
  const float cos_inner = std::cos(glm::radians(s.light.inner_angle_deg));
  for (int y = 0; y < direct.height; ++y)
    for (int x = 0; x < direct.width; ++x) {
      if (pos.at(x, y, 3) == 0.0f) continue;
      const glm::vec3 p(pos.at(x, y, 0), pos.at(x, y, 1), pos.at(x, y, 2));
      const glm::vec3 n(nrm.at(x, y, 0), nrm.at(x, y, 1), nrm.at(x, y, 2));
      const glm::vec3 to_light = s.light.position - p;
      const float r = glm::length(to_light);
      const glm::vec3 l = to_light / r;
      const glm::vec3 expected = glm::vec3(0.5f) / float(M_PI) *
                                 spot_radiant_intensity(s.light, -l) * std::max(0.0f, glm::dot(n, l)) / (r * r);
      for (int ch = 0; ch < 3; ++ch)
        ASSERT_NEAR(direct.at(x, y, ch), expected[ch], 1e-5f * expected[ch] + 1e-7f) << x << "," << y;
      lit += expected.x > 0.0f;
      const float c = glm::dot(-l, glm::normalize(s.light.direction));
      soft += expected.x > 0.0f && c < cos_inner;
    }
  EXPECT_GT(lit, 1000);
  EXPECT_GT(soft, 200);  // the smoothstep's range was exercised
}

}  // namespace
}  // namespace ldm
