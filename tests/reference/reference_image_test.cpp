// Two-half references: determinism, the noise estimate and the automatic spp rule.
#include <cmath>

#include <gtest/gtest.h>

#include "harness/reference/ao_reference.h"
#include "harness/scene/generators.h"
#include "harness/util/error.h"
#include "support/ao_reference_request.h"

namespace ldm {
namespace {

Scene cornell() { return generate_scene("cornell", nlohmann::json::object(), "test"); }

AoReferenceRequest small_request(uint32_t spp_per_half, int threads = 2, uint64_t seed = 1,
                                 AoSampler sampler = AoSampler::Sobol) {
  AoReferenceRequest request = test::ao_reference_request(32, spp_per_half);
  request.sampler = sampler;
  request.seed = seed;
  request.threads = threads;
  return request;
}

TEST(ReferenceImage, SameSeedIsBitIdenticalForAnyThreadCount) {
  const Scene scene = cornell();
  const ReferenceResult one = render_ao_reference(scene, small_request(16, 1));
  const ReferenceResult two = render_ao_reference(scene, small_request(16, 2));
  EXPECT_EQ(one.image.pixels, two.image.pixels);
  EXPECT_EQ(one.half_a.pixels, two.half_a.pixels);
  EXPECT_EQ(one.half_b.pixels, two.half_b.pixels);
  const ReferenceResult other = render_ao_reference(scene, small_request(16, 2, 5));
  EXPECT_NE(one.image.pixels, other.image.pixels);
  EXPECT_NE(one.half_a.pixels, one.half_b.pixels);  // the halves are independent
}

TEST(ReferenceImage, ReferenceIsTheMeanOfItsHalves) {
  const ReferenceResult r = render_ao_reference(cornell(), small_request(8));
  EXPECT_EQ(r.spp_per_half, 8u);
  EXPECT_EQ(r.spp_total, 16u);
  for (size_t i = 0; i < r.image.pixels.size(); ++i)
    EXPECT_NEAR(r.image.pixels[i], 0.5 * (r.half_a.pixels[i] + r.half_b.pixels[i]), 1e-7);
  EXPECT_DOUBLE_EQ(r.noise_mse, mean_squared_error(r.half_a, r.half_b) / 4.0);
  EXPECT_FALSE(r.from_cache);
  EXPECT_FALSE(r.cache_key.empty());
}

// Per-pixel terms (a - b)² / 4 of the noise estimate, their mean and its standard error.
struct NoiseEstimate {
  double mse, standard_error;
};
NoiseEstimate noise_estimate(const ReferenceResult& r) {
  const size_t n = r.half_a.pixels.size();
  double sum = 0.0, sum2 = 0.0;
  for (size_t i = 0; i < n; ++i) {
    const double d = r.half_a.pixels[i] - r.half_b.pixels[i];
    const double term = d * d / 4.0;
    sum += term;
    sum2 += term * term;
  }
  const double mean = sum / n;
  return {mean, std::sqrt((sum2 / n - mean * mean) / (n - 1))};
}

TEST(ReferenceImage, NoiseEstimateHalvesWhenSppDoublesWithRandomSamples) {
  const Scene scene = cornell();
  const NoiseEstimate coarse =
      noise_estimate(render_ao_reference(scene, small_request(16, 2, 1, AoSampler::Random)));
  const NoiseEstimate fine =
      noise_estimate(render_ao_reference(scene, small_request(32, 2, 3, AoSampler::Random)));
  // E[coarse] = 2 E[fine]; both are means of many independent pixel terms.
  const double difference = coarse.mse - 2.0 * fine.mse;
  const double standard_error = std::sqrt(coarse.standard_error * coarse.standard_error +
                                          4.0 * fine.standard_error * fine.standard_error);
  EXPECT_LE(std::abs(difference), 5.0 * standard_error)
      << "noise " << coarse.mse << " at 16 spp, " << fine.mse << " at 32 spp";
  EXPECT_GT(coarse.mse, 0.0);
}

// Scrambled Sobol directions (the default): at equal rays the noise is far below random
// sampling's, and the estimate MSE(A, B) / 4 is still the error of the mean: against a
// reference with 64x the rays, the Sobol image's MSE is its noise estimate plus that
// reference's own, within sampling error.
TEST(ReferenceImage, SobolReachesLessNoiseAtEqualRaysAndItsEstimateIsHonest) {
  const Scene scene = cornell();
  const ReferenceResult sobol = render_ao_reference(scene, small_request(32));
  const ReferenceResult random = render_ao_reference(scene, small_request(32, 2, 1, AoSampler::Random));
  EXPECT_LT(sobol.noise_mse, random.noise_mse / 4) << "sobol " << sobol.noise_mse << ", random "
                                                   << random.noise_mse;
  const ReferenceResult truth =
      render_ao_reference(scene, small_request(2048, 2, 11, AoSampler::Sobol));
  const double error = mean_squared_error(sobol.image, truth.image);
  const double expected = sobol.noise_mse + truth.noise_mse;
  EXPECT_GT(error, 0.5 * expected) << "error " << error << ", noise estimates " << expected;
  EXPECT_LT(error, 2.0 * expected) << "error " << error << ", noise estimates " << expected;
}

TEST(ReferenceImage, AutomaticSppStopsAtTheFirstLevelMeetingTheTarget) {
  const Scene scene = cornell();
  // Random samples: the noise the rule watches then falls as 1/spp, level by level.
  AoReferenceRequest request = small_request(0, 2, 1, AoSampler::Random);
  request.spp.target_noise_mse = 1e-4;
  const ReferenceResult r = render_ao_reference(scene, request);
  EXPECT_TRUE(r.noise_target_met);
  EXPECT_LE(r.noise_mse, 1e-4);
  EXPECT_DOUBLE_EQ(r.noise_mse, mean_squared_error(r.half_a, r.half_b) / 4.0);
  ASSERT_GT(r.spp_per_half, 16u) << "the target should need more than the first level";
  // The rule doubles from 16: the same request capped one level lower repeats the same
  // passes, and must have missed the target (else the rule should have stopped there).
  EXPECT_EQ(r.spp_per_half & (r.spp_per_half - 1), 0u) << "not 16 * 2^k: " << r.spp_per_half;
  request.spp.max_spp_per_half = r.spp_per_half / 2;
  const ReferenceResult lower = render_ao_reference(scene, request);
  EXPECT_EQ(lower.spp_per_half, r.spp_per_half / 2);
  EXPECT_FALSE(lower.noise_target_met);
  EXPECT_GT(lower.noise_mse, 1e-4);
}

TEST(ReferenceImage, AutomaticSppStopsAtTheMaximum) {
  AoReferenceRequest request = small_request(0);
  request.spp.target_noise_mse = 1e-12;  // unreachable
  request.spp.max_spp_per_half = 40;     // 16, 32, then capped at 40
  const ReferenceResult r = render_ao_reference(cornell(), request);
  EXPECT_EQ(r.spp_per_half, 40u);
  EXPECT_EQ(r.spp_total, 80u);
  EXPECT_FALSE(r.noise_target_met);
}

TEST(ReferenceImage, RejectsBadRequestsNamingTheField) {
  const Scene scene = cornell();
  auto message_of = [&](const AoReferenceRequest& request) -> std::string {
    try {
      render_ao_reference(scene, request);
    } catch (const UserError& e) {
      return e.what();
    }
    return "";
  };
  AoReferenceRequest r = small_request(8);
  r.width = 0;
  EXPECT_NE(message_of(r).find("width"), std::string::npos);
  r = small_request(8);
  r.height = -3;
  EXPECT_NE(message_of(r).find("height"), std::string::npos);
  r = small_request(0);
  r.spp.target_noise_mse = 0.0;
  EXPECT_NE(message_of(r).find("target_noise_mse"), std::string::npos);
  r = small_request(8);
  r.spp.max_spp_per_half = 4;
  EXPECT_NE(message_of(r).find("spp_per_half"), std::string::npos);
  r = small_request(8);
  r.ao = AoSettings{};
  r.ao->d_max = -1.0f;
  EXPECT_NE(message_of(r).find("d_max"), std::string::npos);
  r.ao->d_max = 1.0f;
  r.ao->falloff_exponent = NAN;
  EXPECT_NE(message_of(r).find("falloff_exponent"), std::string::npos);
}

TEST(ReferenceImage, AoOverrideReplacesTheScenesSettings) {
  const Scene scene = cornell();
  AoReferenceRequest request = small_request(8);
  AoSettings unattenuated = scene.ao;
  unattenuated.attenuated = false;
  request.ao = unattenuated;
  Scene same = scene;
  same.ao = unattenuated;
  EXPECT_EQ(render_ao_reference(scene, request).image.pixels,
            render_ao_reference(same, small_request(8)).image.pixels);
  EXPECT_NE(render_ao_reference(scene, request).image.pixels,
            render_ao_reference(scene, small_request(8)).image.pixels);
}

}  // namespace
}  // namespace ldm
