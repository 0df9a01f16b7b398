// The LDM AO pass converges towards the path-traced reference as the number of views grows
// (on the default scene, at a fixed LDM resolution high enough that N limits the error).
#include <gtest/gtest.h>

#include "harness/metrics/image_metrics.h"
#include "harness/passes/ao_pass.h"
#include "harness/passes/gbuffer_pass.h"
#include "harness/reference/ao_reference.h"
#include "support/ldm_fixture.h"

namespace ldm {
namespace {

TEST(AoConvergence, ErrorAgainstTheReferenceFallsAsNGrows) {
  const Scene scene = load_scene("cornell");
  const int width = 64, height = 64;
  AoReferenceRequest request;
  request.width = width;
  request.height = height;
  request.spp.spp_per_half = 1024;
  request.progress = false;
  const ReferenceResult reference = render_ao_reference(scene, request);
  std::vector<double> errors;
  for (uint32_t n : {4u, 8u, 16u, 32u}) {
    const test::LdmFixture f(scene, n, 256);
    auto structure = f.build("psppsll");
    GBufferPass gbuffer(width, height);
    AoPass ao(*structure, *f.inputs, width, height, scene.ao);
    gbuffer.render(*f.gpu_scene, scene, nullptr);
    ao.render(gbuffer, nullptr);
    const ImageComparison m = compare_images(reference.image, ao.read_image(), {});
    std::printf("cornell N=%u R=256 %dx%d: MSE %.4e, MSSIM %.4f (reference noise MSE %.1e)\n", n,
                width, height, m.mse, m.mssim, reference.noise_mse);
    errors.push_back(m.mse);
  }
  for (size_t i = 1; i < errors.size(); ++i) {
    // Each step must fall by clearly more than the reference's own noise could explain.
    EXPECT_LT(errors[i], errors[i - 1] - 10 * reference.noise_mse) << "step " << i;
  }
}

}  // namespace
}  // namespace ldm
