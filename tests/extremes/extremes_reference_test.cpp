// Extremes of the reference (issue 12): a scene far from the origin, or scaled to 1e-6 or
// 1e5, has the same AO as at the origin at unit scale (AO is invariant under translation and,
// with d_max scaled alike, under scaling); a d_max near the ray offset is flagged.
#include <gtest/gtest.h>

#include <cmath>

#include "harness/reference/ao_estimator.h"
#include "harness/reference/ao_reference.h"
#include "harness/scene/generators.h"

namespace ldm {
namespace {

constexpr int kReferenceImageSize = 24;

// Parallel planes with a tilted camera, every coordinate a dyadic fraction, so that the
// translations and power-of-two scalings below are exact in float: any difference in the
// images is the tracer's, not the scene's.
Scene dyadic_planes() {
  Scene scene = generate_scene("parallel-planes", {{"h", 1.0}, {"d_max", 2.0}}, "test");
  scene.camera.eye = {0.25f, 0.875f, 0.5f};
  scene.camera.target = {0.0f, 0.0f, -0.25f};
  scene.camera.up = {0.0f, 1.0f, 0.0f};
  return scene;
}

Scene transformed(Scene scene, float scale, glm::vec3 translate) {
  for (auto& p : scene.mesh.positions) p = p * scale + translate;
  scene.camera.eye = scene.camera.eye * scale + translate;
  scene.camera.target = scene.camera.target * scale + translate;
  scene.light.position = scene.light.position * scale + translate;
  scene.ao.d_max *= scale;
  return scene;
}

Image render(const Scene& scene) {
  return render_ao_half(scene, scene.ao, kReferenceImageSize, kReferenceImageSize, 64, /*seed=*/3, 0, /*threads=*/2);
}

double mean_abs_difference(const Image& a, const Image& b) {
  double sum = 0.0;
  for (size_t i = 0; i < a.pixels.size(); ++i) sum += std::abs(double(a.pixels[i]) - b.pixels[i]);
  return sum / double(a.pixels.size());
}

double mean(const Image& a) {
  double sum = 0.0;
  for (float v : a.pixels) sum += v;
  return sum / double(a.pixels.size());
}

TEST(ExtremesReference, FarFromTheOriginTheReferenceEqualsTheOneAtTheOrigin) {
  const Scene origin = dyadic_planes();
  const Image at_origin = render(origin);
  ASSERT_LT(mean(at_origin), 0.9) << "the ceiling must occlude";
  // 2^10 ~ 1e3 (the old offset rule biased it by 1e-3), 2^20 ~ 1e6 (the old offset was
  // 17 units: no ray hit anything and the reference was 1.0 everywhere).
  for (float distance : {1024.0f, 1048576.0f}) {
    const Image far = render(transformed(origin, 1.0f, glm::vec3(distance, distance, -distance)));
    EXPECT_LT(mean_abs_difference(far, at_origin), 1e-6) << "translated by " << distance
                                                         << ": mean " << mean(far);
  }
}

TEST(ExtremesReference, TinyAndHugeScenesHaveTheSameAo) {
  const Scene unit = dyadic_planes();
  const Image at_unit = render(unit);
  // 2^-20 ~ 1e-6 and 2^17 ~ 1.3e5, with d_max scaled alike.
  for (float scale : {1.0f / 1048576.0f, 131072.0f}) {
    const Image scaled = render(transformed(unit, scale, glm::vec3(0.0f)));
    EXPECT_LT(mean_abs_difference(scaled, at_unit), 1e-6) << "scaled by " << scale;
  }
}

TEST(ExtremesReference, RayOffsetScalesWithTheSceneNotItsPosition) {
  const Scene unit = dyadic_planes();
  const float at_origin = max_ray_offset(centred_on_bounding_sphere(unit));
  const float far = max_ray_offset(
      centred_on_bounding_sphere(transformed(unit, 1.0f, glm::vec3(1e6f))));
  EXPECT_GT(at_origin, 0.0f);
  EXPECT_EQ(far, at_origin);
  // A small fraction of the scene: the floor's half size is 4.
  EXPECT_LT(at_origin, 1e-5f * 4.0f);
}

}  // namespace
}  // namespace ldm
