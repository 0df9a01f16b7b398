// HBAO (harness/passes/hbao.h) on scenes whose answer is known.
#include <gtest/gtest.h>

#include <cmath>

#include "harness/passes/hbao.h"
#include "harness/passes/hbao_kernel.h"
#include "harness/reference/ao_reference.h"
#include "harness/scene/scene_loader.h"
#include "harness/util/error.h"
#include "support/hand_gbuffer.h"
#include "support/pass_run.h"
#include "support/test_support.h"

namespace ldm {
namespace {

constexpr int kSize = 64;

// The HBAO image of `scene` (kSize x kSize) with the given parameters.
Image hbao_image(const Scene& scene, std::map<std::string, std::string> params) {
  return test::PassRun<Hbao>("hbao", scene, kSize, kSize, std::move(params)).render();
}

// Covered pixels (AO > 0: the pass writes 0 for background and at least 1 - 1 = 0 would
// need a fully occluded pixel, which these scenes do not have).
int covered(const Image& image) {
  int count = 0;
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) count += image.at(x, y, 0) > 0.0f;
  return count;
}

// On an open plane every sample of the depth buffer lies in x's own tangent plane, so no
// sample rises above the (biased) tangent angle: AO is exactly 1, for any view of the plane.
// An oblique camera makes the tangent angle differ per direction, so a wrong sign or slice
// in the tangent shows up as occlusion here.
TEST(Hbao, OpenPlaneIsExactlyUnoccluded) {
  Scene scene = load_scene("plane");
  scene.camera.eye = {0.0f, 1.0f, 2.0f};
  scene.camera.target = {0.0f, 0.0f, 0.0f};
  scene.camera.up = {0.0f, 1.0f, 0.0f};
  for (const char* jitter : {"off", "on"}) {
    const Image image =
        hbao_image(scene, {{"directions", "8"}, {"steps", "8"}, {"jitter", jitter}});
    ASSERT_GT(covered(image), kSize * kSize / 4) << "jitter " << jitter;
    for (int y = 0; y < image.height; ++y)
      for (int x = 0; x < image.width; ++x) {
        const float ao = image.at(x, y, 0);
        if (ao > 0.0f) ASSERT_EQ(ao, 1.0f) << "pixel " << x << "," << y << " jitter " << jitter;
      }
  }
}

// The known failure of a screen-space method: the camera under the ceiling sees only the
// floor, so the depth buffer holds no occluder and HBAO says 1 everywhere. The truth (with
// the scene's attenuated V = min(d / d_max, 1)^2, d_max = 2h) is, for a ray at angle theta
// from the normal hitting the ceiling at d = h / cos(theta),
//   AO = 2 int_0^(pi/2) V cos sin dtheta = 2 (ln(2)/4 + 1/8) = ln(2)/2 + 1/4 ~ 0.597
// (V < 1 only for cos(theta) > 1/2, where the ceiling, 4h wide, is hit from every visible
// floor point), so HBAO is biased by +0.403 on every pixel. The Embree reference confirms the
// closed form, so the bias is the method's, not the scene's.
TEST(Hbao, ParallelPlanesMissTheCeilingTheDepthBufferCannotSee) {
  const Scene scene = load_scene("parallel-planes");
  ASSERT_TRUE(scene.ao.attenuated);
  ASSERT_FLOAT_EQ(scene.ao.d_max, 2.0f);
  const double truth = std::log(2.0) / 2.0 + 0.25;

  const Image image = hbao_image(scene, {{"directions", "16"}, {"steps", "16"}});
  ASSERT_EQ(covered(image), kSize * kSize);  // the floor fills the view
  double hbao_mean = 0;
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize; ++x) hbao_mean += image.at(x, y, 0);
  hbao_mean /= kSize * kSize;
  EXPECT_EQ(hbao_mean, 1.0);

  const int side = 16;
  const Image reference = render_ao_half(scene, scene.ao, side, side, 64, 1);
  double reference_mean = 0;
  for (int y = 0; y < side; ++y)
    for (int x = 0; x < side; ++x) reference_mean += reference.at(x, y, 0);
  reference_mean /= side * side;
  // 16384 cosine samples of V in [1/4, 1]: the mean's standard error is below 0.002.
  EXPECT_NEAR(reference_mean, truth, 0.01);
  EXPECT_NEAR(hbao_mean - reference_mean, 1.0 - truth, 0.01) << "the expected bias, +0.403";
}

// W = 1 - r^2 / R^2 only lowers each rise in the horizon, so attenuated HBAO is never darker
// than unattenuated HBAO, and differs from it where occluders lie within R.
TEST(Hbao, FalloffOnlyLightensAndMatters) {
  const Scene scene = load_scene("cornell");
  const Image attenuated = hbao_image(scene, {{"visibility", "attenuated"}});
  const Image unattenuated = hbao_image(scene, {{"visibility", "unattenuated"}});
  int lighter = 0;
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize; ++x) {
      const float a = attenuated.at(x, y, 0), u = unattenuated.at(x, y, 0);
      ASSERT_GE(a, u - 1e-6f) << "pixel " << x << "," << y;
      lighter += a > u + 1e-3f;
    }
  EXPECT_GT(lighter, kSize * kSize / 20);
}

using test::HandGBuffer;

// The camera at the origin looking down -z; a floor facing it at depth 4 whose pixels are
// `s` apart; with R = 2 and focal 8 px, R projects to 4 px at depth 4, so S = 4 steps read
// the pixels 1, 2, 3, 4 to the right of x (direction 0 of N = 1).
float hand_case_ao(const std::vector<std::pair<int, glm::vec3>>& raised, float angle_bias,
                   float falloff_exponent) {
  test::gl_context();
  const float s = 0.25f;
  HandGBuffer g(8, 3);
  for (int y = 0; y < 3; ++y)
    for (int x = 0; x < 8; ++x) g.set(x, y, {(float(x) - 1.0f) * s, (float(y) - 1.0f) * s, -4.0f});
  for (const auto& [dx, offset] : raised) g.set(1 + dx, 1, glm::vec3(float(dx) * s, 0.0f, -4.0f) + offset);
  HbaoSettings hbao;
  hbao.directions = 1;
  hbao.steps = 4;
  hbao.angle_bias = angle_bias;
  AoSettings ao;
  ao.d_max = 2.0f;
  ao.attenuated = true;
  ao.falloff_exponent = falloff_exponent;
  HbaoKernel kernel(hbao, ao, g.width, g.height);
  kernel.set_camera({{0.0f, 0.0f, 0.0f}, {0.0f, 0.0f, -1.0f}, 8.0f});
  const GlTexture2D positions = g.upload(g.positions), normals = g.upload(g.normals);
  kernel.run(positions, normals);
  const std::vector<float> ao_texels = kernel.target().read_floats(1);
  return ao_texels[1 * g.width + 1];  // x = pixel (1, 1)
}

// Eq. 11 by hand for x on the floor (tangent angle 0, plus the bias), one direction:
// the sample 2 px right raised to (0.5 lateral, 0.5 toward the camera) from x has r^2 = 0.5,
// sin h = 1/sqrt(2), W = 1 - 0.5/4 = 0.875; the one 3 px right at (0.75, 1.5) has
// r^2 = 2.8125, tan h = 2, sin h = 2/sqrt(5), W = 1 - 2.8125/4 = 0.296875, and adds only its
// rise above the first; the one 4 px right at (1, 0.25) lies below the horizon and adds
// nothing. AO = 1 - sum W (sin h_new - sin h_old).
TEST(Hbao, AttenuationMatchesAHandComputedCase) {
  const std::vector<std::pair<int, glm::vec3>> raised = {
      {2, {0.0f, 0.0f, 0.5f}}, {3, {0.0f, 0.0f, 1.5f}}, {4, {0.0f, 0.0f, 0.25f}}};
  const double sin1 = 1.0 / std::sqrt(2.0), sin2 = 2.0 / std::sqrt(5.0);
  const double expected = 1.0 - (0.875 * sin1 + 0.296875 * (sin2 - sin1));
  EXPECT_NEAR(hand_case_ao(raised, 0.0f, 2.0f), expected, 2e-6);
  // The angle bias starts the horizon at sin(0.1) instead of 0.
  const double biased = 1.0 - (0.875 * (sin1 - std::sin(0.1)) + 0.296875 * (sin2 - sin1));
  EXPECT_NEAR(hand_case_ao(raised, 0.1f, 2.0f), biased, 2e-6);
  // Falloff exponent 1 (the LDM AO's V = (d/d_max)^1): W = 1 - r/R.
  const double linear = 1.0 - ((1.0 - std::sqrt(0.5) / 2.0) * sin1 +
                               (1.0 - std::sqrt(2.8125) / 2.0) * (sin2 - sin1));
  EXPECT_NEAR(hand_case_ao(raised, 0.0f, 1.0f), linear, 2e-6);
  // Beyond R (r^2 = 4.25 > 4) a sample is ignored however high.
  EXPECT_EQ(hand_case_ao({{2, {0.0f, 0.0f, 2.0f}}}, 0.0f, 2.0f), 1.0f);
}

// The blur on a hand-made G-buffer: two facing planes side by side at depths 2 and 6 (a
// depth edge between columns 7 and 8), AO 0.2 on the near one and 0.9 on the far one, plus
// a checkerboard of +-0.05 on both. A plain Gaussian would mix the two across the edge; the
// cross-bilateral weights keep each side its own mean (the far plane's 0.2 weight is
// exp(-(4/footprint)^2) ~ 0), and the checkerboard shrinks.
TEST(Hbao, BlurSmoothsWithoutCrossingADepthEdge) {
  test::gl_context();
  const int w = 16, h = 8;
  HandGBuffer g(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const float depth = x < 8 ? 2.0f : 6.0f;
      g.set(x, y, {(float(x) - 8.0f) * depth / 8.0f, (float(y) - 4.0f) * depth / 8.0f, -depth});
    }
  std::vector<float> ao(w * h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) ao[y * w + x] = (x < 8 ? 0.2f : 0.9f) + ((x + y) % 2 ? 0.05f : -0.05f);
  GlTexture2D target(GL_R32F, w, h);
  glTextureSubImage2D(target.id(), 0, 0, 0, w, h, GL_RED, GL_FLOAT, ao.data());
  const GlTexture2D positions = g.upload(g.positions), normals = g.upload(g.normals);
  HbaoBlur blur(3, target);
  blur.set_camera({{0.0f, 0.0f, 0.0f}, {0.0f, 0.0f, -1.0f}, 8.0f});
  blur.run(positions, normals);
  const std::vector<float> out = target.read_floats(1);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const float side = x < 8 ? 0.2f : 0.9f;
      EXPECT_NEAR(out[y * w + x], side, 0.025f) << "pixel " << x << "," << y;
    }
}

TEST(Hbao, BlurIsASubpassAndItsTargetsAreCounted) {
  test::expect_smoothing_subpass<Hbao>("hbao", load_scene("cornell"), kSize, "blur",
                                       {"gbuffer", "hbao", "blur"});
}

TEST(Hbao, ParametersAreChecked) {
  test::expect_parameters_checked("hbao",
                                  {{"directions", "0"}, {"steps", "513"}, {"angle_bias", "-0.1"},
                                   {"jitter", "yes"}, {"d_max", "0"}, {"trace", "plane"}, {"blur", "17"}},
                                  "steps", 4, "hbao_steps", false);
}

}  // namespace
}  // namespace ldm
