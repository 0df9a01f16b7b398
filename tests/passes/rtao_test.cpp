// The ray-traced AO peer (harness/passes/rtao.h): the reference's estimator at few samples per
// pixel, on scenes whose answer is known, and independent of the reference it is scored by.
#include <gtest/gtest.h>

#include <cmath>

#include "harness/passes/rtao.h"
#include "harness/reference/ao_reference.h"
#include "harness/scene/scene_loader.h"
#include "harness/util/error.h"
#include "support/ao_reference_request.h"
#include "support/pass_run.h"
#include "support/test_support.h"

namespace ldm {
namespace {

// The RTAO image of `scene` (size x size) with the given parameters.
Image rtao_image(const Scene& scene, int size, std::map<std::string, std::string> params) {
  // The peer measurement uploads the scene; rtao itself draws nothing.
  test::PassRun<Rtao> run("rtao", scene, size, size, std::move(params), AttributeSet{});
  GpuTimer timer(TimerSource::CpuWallClock);
  timer.begin_frame();
  const Image image = run.render(&timer);
  const FrameTimes times = timer.end_frame();
  EXPECT_EQ(times.size(), 1u);
  EXPECT_EQ(times.front().first, "rtao");
  EXPECT_GT(times.front().second, 0.0) << "CPU wall time of the trace";
  return image;
}

double mean_of(const Image& image) {
  double sum = 0;
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) sum += image.at(x, y, 0);
  return sum / (image.width * image.height);
}

// Nothing above an open plane: every ray escapes, at any sample count.
TEST(Rtao, OpenPlaneIsExactlyUnoccluded) {
  Scene scene = load_scene("plane");
  scene.camera.eye = {0.0f, 1.0f, 2.0f};
  scene.camera.target = {0.0f, 0.0f, 0.0f};
  const Image image = rtao_image(scene, 24, {{"spp", "3"}});
  int covered = 0;
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) {
      const float ao = image.at(x, y, 0);
      if (ao == 0.0f) continue;  // background
      ++covered;
      ASSERT_EQ(ao, 1.0f) << "pixel " << x << "," << y;
    }
  EXPECT_GT(covered, 24 * 24 / 4);
}

// The reference's attenuation convention V = min(d / d_max, 1)^2 (see hbao_test.cpp for the
// closed form ln 2 / 2 + 1/4 under the ceiling at h = d_max / 2): 16 x 16 pixels at 16 spp
// are 4096 samples of V in [1/4, 1], a standard error below 0.006.
TEST(Rtao, ParallelPlanesMeetTheClosedForm) {
  const Scene scene = load_scene("parallel-planes");
  const double truth = std::log(2.0) / 2.0 + 0.25;
  EXPECT_NEAR(mean_of(rtao_image(scene, 16, {{"spp", "16"}})), truth, 0.02);
  // Unattenuated, a ray is visible only if it escapes past the finite ceiling's edge: dark.
  EXPECT_LT(mean_of(rtao_image(scene, 8, {{"spp", "16"}, {"visibility", "unattenuated"}})), 0.1);
}

// RTAO's samples must not be the reference's own: an image drawn from one of the reference's
// halves would be scored against a mean that contains it. With n spp against a reference of
// two n-spp halves, independent samples give E[MSE] = s2/n + s2/(2n) = 3 noise_mse; RTAO
// equal to half A would give MSE(A, (A+B)/2) = noise_mse. Even when --reference-seed is
// RTAO's own seed.
TEST(Rtao, SamplesAreIndependentOfTheReferenceHalves) {
  const Scene scene = load_scene("cornell");
  const int size = 32;
  const uint32_t spp = 4;
  AoReferenceRequest request = test::ao_reference_request(size, spp);
  request.seed = 0x5254414f;  // RTAO's default seed
  // The reference's own random sampler, RTAO's: the ratios above assume both halves' samples
  // are independent draws of RTAO's kind (the default scrambled Sobol halves are far less
  // noisy, and cannot coincide with RTAO's random numbers).
  request.sampler = AoSampler::Random;
  const ReferenceResult reference = render_ao_reference(scene, request);
  const Image rtao = rtao_image(scene, size, {{"spp", std::to_string(spp)}});
  const double ratio = mean_squared_error(rtao, reference.image) / reference.noise_mse;
  EXPECT_GT(ratio, 2.3) << "RTAO shares samples with the reference";
  EXPECT_LT(ratio, 3.7);
}

// Monte Carlo error: MSE against a converged reference falls as 1/spp.
TEST(Rtao, ErrorFallsAsOneOverSpp) {
  const Scene scene = load_scene("cornell");
  const int size = 32;
  const ReferenceResult reference = render_ao_reference(scene, test::ao_reference_request(size, 512));
  const double mse1 = mean_squared_error(rtao_image(scene, size, {{"spp", "1"}}), reference.image);
  const double mse4 = mean_squared_error(rtao_image(scene, size, {{"spp", "4"}}), reference.image);
  EXPECT_GT(mse1 / mse4, 3.0);
  EXPECT_LT(mse1 / mse4, 5.3);
}

TEST(Rtao, ParametersAreCheckedAndItRunsOnTheCpu) {
  test::expect_parameters_checked("rtao",
                                  {{"spp", "0"}, {"spp", "65537"}, {"threads", "-1"},
                                   {"visibility", "half"}, {"d_max", "0"}, {"trace", "plane"}},
                                  "spp", 8, "rtao_spp", true);
}

}  // namespace
}  // namespace ldm
