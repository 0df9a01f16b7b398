// The flux audit (issue 20; harness/passes/photon_lighting.h PhotonFluxTally, SplatAudit):
// every emitted watt has one fate; the audit splat's deposited flux is the indirect image's
// own integral over the surfaces it shows, whose pixel areas add up to a plane's closed form;
// one photon's flux splits into exactly the parts the audit names (off the image, cut by the
// topological bias); the normalised emission emits exactly rho * Phi1; and the camera depth
// test holds at its threshold.
#include <gtest/gtest.h>

#include <cmath>

#include "harness/passes/photon_lighting.h"
#include "harness/scene/camera.h"
#include "indirect/indirect_support.h"

namespace ldm {
namespace {

double channel_mean(glm::vec3 v) { return (double(v.x) + v.y + v.z) / 3.0; }

// Every secondary photon's flux is tallied under exactly one fate, the stored ones' equal to
// what the photon buffer holds, and the counts split culled_depth the same way.
void expect_tally_closes(const test::IndirectRun& run) {
  const PhotonLighting& lighting = run.lighting();
  const PhotonFluxTally t = lighting.flux_tally();
  const PhotonCounts c = lighting.counts();
  ASSERT_GT(t.emitted, 0.0);
  const double fates = t.escaped + t.culled_outside + t.culled_hidden + t.culled_backside +
                       t.culled_footprint + t.degenerate + t.stored + t.overflow;
  EXPECT_NEAR(fates, t.emitted, 1e-5 * t.emitted);
  double stored = 0;
  for (const auto& p : lighting.read_photons()) stored += channel_mean(p.flux);
  EXPECT_NEAR(t.stored, stored, 1e-5 * stored);
  EXPECT_EQ(c.culled_depth, c.culled_outside + c.culled_hidden() + c.culled_backside);
  EXPECT_LE(c.culled_outside + c.culled_backside, c.culled_depth);
  // A fate's flux is zero exactly when its count is.
  EXPECT_EQ(c.escaped == 0, t.escaped == 0.0);
  EXPECT_EQ(c.culled_outside == 0, t.culled_outside == 0.0);
  EXPECT_EQ(c.culled_backside == 0, t.culled_backside == 0.0);
}

TEST(IndirectAudit, EveryEmittedWattHasOneFate) {
  const test::IndirectRun cornell(load_scene("cornell"), "psppsll", 8, 64, 64, {{"r_light", "24"}});
  expect_tally_closes(cornell);
  // The Cornell box seen from its open side: photons land outside the image and behind the
  // blocks, and reach the walls' backs through no gap: outside and hidden both occur.
  EXPECT_GT(cornell.lighting().counts().culled_outside, 0u);
  EXPECT_GT(cornell.lighting().counts().culled_hidden(), 0u);
  const test::IndirectRun sphere(load_scene("closed-sphere"), "psppsll", 8, 64, 64, {{"r_light", "24"}});
  expect_tally_closes(sphere);
}

// The emission: `normalized` splits exactly rho * Phi1; `thesis` its quadrature, which on
// the sphere's hits (every orientation) sums to rho * Phi1 only on average.
TEST(IndirectAudit, NormalizedEmissionEmitsExactlyTheReflectedFlux) {
  const Scene scene = load_scene("closed-sphere");
  const test::IndirectRun normalized(scene, "psppsll", 8, 64, 48, {{"r_light", "24"}, {"emission", "normalized"}});
  const PhotonFluxTally n = normalized.lighting().flux_tally();
  EXPECT_NEAR(n.emitted, n.reflected, 1e-5 * n.reflected);
  const test::IndirectRun thesis(scene, "psppsll", 8, 64, 48, {{"r_light", "24"}});
  const PhotonFluxTally t = thesis.lighting().flux_tally();
  EXPECT_NEAR(t.reflected, n.reflected, 1e-6 * n.reflected);  // the same primaries
  EXPECT_GT(std::abs(t.emitted / t.reflected - 1.0), 1e-3);   // a quadrature, not exact
  // Per texel, normalized = thesis rescaled by N / (2 sum |cos|): the stored photons' flux
  // ratio equals the emitted ratio photon by photon (same photons, same order of texels).
  const auto tally_n = normalized.lighting().read_tally(), tally_t = thesis.lighting().read_tally();
  constexpr uint32_t K = PhotonLighting::kTallyEntries;
  for (size_t i = 0; i + K <= tally_n.size(); i += K) {
    const double e_t = channel_mean(glm::vec3(tally_t[i + 1])), e_n = channel_mean(glm::vec3(tally_n[i + 1]));
    const double s_t = channel_mean(glm::vec3(tally_t[i + 8])), s_n = channel_mean(glm::vec3(tally_n[i + 8]));
    if (e_t > 0 && s_t > 0) ASSERT_NEAR(s_n / s_t, e_n / e_t, 1e-4 * e_n / e_t) << "texel " << i / K;
  }
}

// The audit splat's pixel areas: on a plane square to the view axis at height h, the image
// shows exactly (2 h tan(fov / 2))^2 (each pixel's patch is its solid angle times d^2 / cos,
// which there is h^2 times its image-plane area).
TEST(IndirectAudit, PixelAreasAddUpToThePlanesClosedForm) {
  Scene scene = load_scene("plane");
  scene.camera.eye = {0.0f, 1.5f, 0.0f};
  const test::IndirectRun run(scene, "psppsll", 2, 32, 64, {{"r_light", "16"}});
  Image areas;
  const SplatAudit audit = run.lighting().audit_splat(run.pass->camera_gbuffer(), &areas);
  const double side = 2.0 * 1.5 * std::tan(glm::radians(double(scene.camera.fov_y_deg) / 2.0));
  EXPECT_NEAR(audit.visible_area, side * side, 1e-4 * side * side);
  double sum = 0;
  for (float a : areas.pixels) sum += a;
  EXPECT_NEAR(sum, audit.visible_area, 1e-4 * audit.visible_area);
}

// What the image holds is what the audit calls deposited: the integral of pi L / rho over the
// surfaces the image shows, from the indirect image itself (Cornell box: coloured walls).
TEST(IndirectAudit, DepositedFluxIsTheImagesIntegral) {
  const test::IndirectRun run(load_scene("cornell"), "psppsll", 8, 64, 64, {{"r_light", "24"}});
  Image areas;
  const SplatAudit audit = run.lighting().audit_splat(run.pass->camera_gbuffer(), &areas);
  const Image image = run.indirect();
  const Image albedo = run.pass->camera_gbuffer().read_albedo();
  double integral = 0;
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x)
      for (int c = 0; c < 3; ++c)
        if (albedo.at(x, y, c) > 0.0f)
          integral += M_PI * image.at(x, y, c) / albedo.at(x, y, c) * areas.at(x, y) / 3.0;
  ASSERT_GT(integral, 0.0);
  EXPECT_NEAR(audit.deposited, integral, 1e-3 * integral);
  // The chain: stored >= what lies over seen surface >= inside the quads; the cut only removes.
  const double stored = run.lighting().flux_tally().stored;
  EXPECT_LE(audit.tangent_in_quad, audit.tangent_all * (1 + 1e-5));
  EXPECT_LE(audit.deposited, audit.uncut * (1 + 1e-5));
  EXPECT_LT(audit.tangent_all, stored * 1.02);  // at most the pixel quadrature's error above
}

// One photon on a plane seen straight down: its flux is all deposited where it lies in view;
// lifted off the plane the topological bias cuts all of it (clipped); half off the image, the
// audit finds half over no visible surface (unseen).
TEST(IndirectAudit, OnePhotonsFluxGoesWhereTheAuditSays) {
  Scene scene = load_scene("plane");
  scene.camera.eye = {0.0f, 1.5f, 0.0f};
  const test::IndirectRun run(scene, "psppsll", 2, 32, 160, {{"r_light", "16"}, {"s", "1"}, {"a", "1"}});
  auto& lighting = const_cast<PhotonLighting&>(run.lighting());
  const GBufferPass& camera = run.pass->camera_gbuffer();
  auto photon = [](glm::vec3 position) {
    StoredPhoton p{};
    p.position = position;
    p.normal = {0.0f, 1.0f, 0.0f};
    p.du_x = {0.2f, 0.0f, 0.05f};
    p.dv_x = {-0.04f, 0.0f, 0.18f};
    p.flux = {1.0f, 0.5f, 0.25f};
    return p;
  };
  const double phi = channel_mean(photon({}).flux);
  lighting.splat_photons(camera, {photon({0.1f, 0.0f, -0.1f})});
  SplatAudit a = lighting.audit_splat(camera);
  EXPECT_NEAR(a.tangent_all, phi, 0.01 * phi);
  EXPECT_NEAR(a.tangent_in_quad, a.tangent_all, 1e-4 * phi);
  EXPECT_NEAR(a.uncut, a.tangent_in_quad, 1e-4 * phi);  // a plane: no extra surface area
  EXPECT_NEAR(a.deposited, a.uncut, 1e-4 * phi);        // on the photon's plane: nothing cut
  // Lifted by 0.15 with a = 1 and a mean semi-axis of sqrt(|Du x Dv|) / 2 ~ 0.095: l > 1.
  lighting.splat_photons(camera, {photon({0.1f, 0.15f, -0.1f})});
  a = lighting.audit_splat(camera);
  EXPECT_EQ(a.deposited, 0.0);
  EXPECT_GT(a.uncut, 0.5 * phi);  // the whole kernel, cut
  // Centred on the image's right edge (x = h tan(fov / 2)): half of it over no surface seen.
  const float edge = 1.5f * std::tan(glm::radians(scene.camera.fov_y_deg / 2.0f));
  lighting.splat_photons(camera, {photon({edge, 0.0f, 0.0f})});
  a = lighting.audit_splat(camera);
  EXPECT_NEAR(a.tangent_all, 0.5 * phi, 0.03 * phi);
  EXPECT_NEAR(a.deposited, a.tangent_all, 1e-4 * phi);
}

// The camera depth test at its threshold (the default, 3 LDM pixels, unless overridden): a hit
// 2 % inside it beyond the surface the camera sees (along the pixel's ray: the thesis's
// distance from the eye) is kept, 2 % beyond it is hidden; one arriving from below the floor
// is on its back side; one beside the image is outside. Catches a halved (or doubled)
// default as much as a shader that compares against half of it.
TEST(IndirectAudit, TheDepthTestHoldsAtItsThreshold) {
  Scene scene = load_scene("plane");
  scene.camera.eye = {0.3f, 1.5f, 0.2f};
  scene.camera.target = {0.0f, 0.0f, 0.0f};
  for (const std::string explicit_threshold : {"", "0.05"}) {
    SCOPED_TRACE("depth_threshold " + (explicit_threshold.empty() ? std::string("default") : explicit_threshold));
    std::map<std::string, std::string> params = {{"r_light", "16"}};
    if (!explicit_threshold.empty()) params["depth_threshold"] = explicit_threshold;
    const test::IndirectRun run(scene, "psppsll", 4, 64, 48, params);
    const double pixel = run.setup->views.views.at(0).pixel_size();
    const double tau = explicit_threshold.empty() ? 3.0 * pixel : std::stod(explicit_threshold);
    EXPECT_NEAR(run.lighting().depth_threshold(), tau, 1e-6 * tau);
    const Image pos = run.pass->camera_gbuffer().read_positions();
    const glm::vec3 eye = run.setup->scene.camera.eye;
    const glm::vec3 down(0.0f, -1.0f, 0.0f);  // arriving from above: the seen side
    std::vector<glm::vec3> x2, w_o;
    std::vector<uint32_t> expected;
    for (int y = 6; y < pos.height; y += 9)
      for (int x = 5; x < pos.width; x += 9) {
        ASSERT_NE(pos.at(x, y, 3), 0.0f);
        const glm::vec3 seen(pos.at(x, y, 0), pos.at(x, y, 1), pos.at(x, y, 2));
        const glm::vec3 away = glm::normalize(seen - eye);
        for (double f : {0.98, 1.02}) {
          x2.push_back(seen + float(f * tau) * away);
          w_o.push_back(down);
          expected.push_back(f < 1.0 ? 0u : 4u);
        }
        x2.push_back(seen);  // from below the floor: its back side
        w_o.push_back(-down);
        expected.push_back(5u);
      }
    x2.push_back({50.0f, 0.0f, 0.0f});  // far beside the image
    w_o.push_back(down);
    expected.push_back(3u);
    const auto verdicts = run.lighting().probe_visibility(run.pass->camera_gbuffer(), x2, w_o);
    ASSERT_EQ(verdicts.size(), expected.size());
    for (size_t i = 0; i < expected.size(); ++i) EXPECT_EQ(verdicts[i], expected[i]) << "point " << i;
  }
}

}  // namespace
}  // namespace ldm
