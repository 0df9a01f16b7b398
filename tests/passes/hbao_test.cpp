// HBAO (harness/passes/hbao.h) on scenes whose answer is known.
#include <gtest/gtest.h>

#include <cmath>

#include "harness/passes/hbao.h"
#include "harness/reference/ao_reference.h"
#include "harness/scene/scene_loader.h"
#include "harness/util/error.h"
#include "support/test_support.h"

namespace ldm {
namespace {

constexpr int kSize = 64;

// The HBAO image of `scene` (kSize x kSize) with the given parameters.
Image hbao_image(const Scene& scene, std::map<std::string, std::string> params) {
  test::gl_context();
  StructureParams p(std::move(params), "hbao test");
  Hbao pass(p);
  p.finish("pass hbao");
  AttributeSet attributes;
  attributes.normals = true;
  const GpuScene gpu_scene(scene, attributes);
  pass.prepare({scene, gpu_scene, nullptr, nullptr, kSize, kSize});
  pass.render(nullptr);
  return pass.images().front().image;
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

TEST(Hbao, ParametersAreChecked) {
  for (const auto& [key, value] : std::vector<std::pair<std::string, std::string>>{
           {"directions", "0"}, {"steps", "513"}, {"angle_bias", "-0.1"}, {"jitter", "yes"},
           {"d_max", "0"}, {"trace", "plane"}}) {
    EXPECT_THROW(make_pass("hbao", StructureParams({{key, value}}, "--pass hbao")), UserError)
        << key << "=" << value;
  }
  const auto pass = make_pass("hbao", StructureParams(std::map<std::string, std::string>{{"steps", "4"}}));
  EXPECT_FALSE(pass->requirements().needs_structure);
  const Scene scene = load_scene("cornell");
  bool found = false;
  for (const auto& [key, value] : pass->describe(scene))
    if (key == "hbao_steps") found = std::get<int64_t>(value) == 4;
  EXPECT_TRUE(found);
}

}  // namespace
}  // namespace ldm
