// The LDM view set: the EQ partition of the hemisphere (count, equal areas, small regions,
// no parallel directions) and the orthographic views fitted to the scene's bounding sphere.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "harness/scene/scene_loader.h"
#include "harness/views/sphere_partition.h"
#include "harness/views/view_set.h"

namespace ldm {
namespace {

constexpr double kPi = 3.14159265358979323846;
const uint32_t kCounts[] = {1, 2, 3, 5, 8, 13, 16, 32, 50, 64, 100, 128, 256, 512};

glm::dvec3 random_direction(std::mt19937_64& rng) {
  std::normal_distribution<double> normal;
  glm::dvec3 d(normal(rng), normal(rng), normal(rng));
  return glm::normalize(d);
}

TEST(SpherePartition, HasExactlyNRegionsAndCentres) {
  for (uint32_t n : kCounts) {
    HemispherePartition p(n);
    EXPECT_EQ(p.size(), n);
    EXPECT_EQ(p.centres().size(), n);
    uint32_t regions = 0;
    for (const auto& z : p.zones()) regions += z.regions;
    EXPECT_EQ(regions, n);
  }
}

TEST(SpherePartition, RegionAreasAreEqualAndSumToTheHemisphere) {
  for (uint32_t n : kCounts) {
    HemispherePartition p(n);
    double total = 0;
    for (uint32_t i = 0; i < n; ++i) {
      EXPECT_NEAR(p.region_area(i), 2 * kPi / n, 1e-12) << "N=" << n << " region " << i;
      total += p.region_area(i);
    }
    EXPECT_NEAR(total, 2 * kPi, 1e-9);
  }
}

// Independent of the bookkeeping above: uniform random lines fall into each region with
// probability 1/N (checked within 5 binomial standard deviations).
TEST(SpherePartition, MonteCarloRegionFrequenciesAreEqual) {
  std::mt19937_64 rng(42);
  for (uint32_t n : {5u, 32u, 100u}) {
    HemispherePartition p(n);
    const int samples = 200000;
    std::vector<int> hits(n, 0);
    for (int s = 0; s < samples; ++s) ++hits[p.region_of(random_direction(rng))];
    const double expected = double(samples) / n;
    const double sigma = std::sqrt(samples * (1.0 / n) * (1.0 - 1.0 / n));
    for (uint32_t i = 0; i < n; ++i)
      EXPECT_NEAR(hits[i], expected, 5 * sigma) << "N=" << n << " region " << i;
  }
}

TEST(SpherePartition, EveryCentreLiesInItsOwnRegion) {
  for (uint32_t n : kCounts) {
    HemispherePartition p(n);
    for (uint32_t i = 0; i < n; ++i) EXPECT_EQ(p.region_of(p.centres()[i]), i) << "N=" << n;
  }
}

TEST(SpherePartition, NoTwoDirectionsAreParallel) {
  for (uint32_t n : kCounts) {
    HemispherePartition p(n);
    for (uint32_t i = 0; i < n; ++i) {
      EXPECT_GT(p.centres()[i].y, 0.0);  // all in the open upper hemisphere
      EXPECT_NEAR(glm::length(p.centres()[i]), 1.0, 1e-12);
      for (uint32_t j = i + 1; j < n; ++j)
        EXPECT_LT(std::abs(glm::dot(p.centres()[i], p.centres()[j])), 1.0 - 1e-9)
            << "N=" << n << " regions " << i << ", " << j;
    }
  }
}

// Leopardi (2006) bounds the diameter of EQ(2, M) regions by about 5.4 / sqrt(M); our
// hemisphere partition with its mirror is an EQ-like partition of the sphere into M = 2N.
TEST(SpherePartition, RegionsHaveSmallDiameter) {
  std::mt19937_64 rng(7);
  for (uint32_t n : {8u, 32u, 128u}) {
    HemispherePartition p(n);
    const double bound = 5.4 / std::sqrt(2.0 * n);
    std::vector<double> farthest(n, 0.0);
    for (int s = 0; s < 100000; ++s) {
      glm::dvec3 d = random_direction(rng);
      if (d.y < 0) d = -d;
      const uint32_t r = p.region_of(d);
      farthest[r] = std::max(farthest[r], glm::length(d - p.centres()[r]));
    }
    for (uint32_t i = 0; i < n; ++i) EXPECT_LE(farthest[i], bound) << "N=" << n << " region " << i;
  }
}

TEST(ViewSet, ViewsAreOrthonormalAndProjectPixelCentres) {
  BoundingSphere sphere{{1.0f, 2.0f, -0.5f}, 3.0f};
  const ViewSet set = make_view_set(sphere, 16, 64);
  ASSERT_EQ(set.size(), 16u);
  for (const auto& v : set.views) {
    EXPECT_NEAR(glm::length(v.forward), 1.0f, 1e-6f);
    EXPECT_NEAR(glm::dot(v.forward, v.right), 0.0f, 1e-6f);
    EXPECT_NEAR(glm::dot(v.forward, v.up), 0.0f, 1e-6f);
    EXPECT_NEAR(glm::dot(v.right, v.up), 0.0f, 1e-6f);
    EXPECT_NEAR(glm::length(v.forward + v.direction), 0.0f, 1e-6f);
    for (uint32_t i : {0u, 17u, 63u})
      for (uint32_t j : {0u, 40u, 63u}) {
        const glm::vec3 p = v.pixel_centre(i, j) + v.forward * 1.5f;
        const glm::vec4 clip = v.view_projection * glm::vec4(p, 1.0f);
        // Window coordinates of the point: exactly the pixel centre (i + 0.5, j + 0.5).
        EXPECT_NEAR((clip.x * 0.5f + 0.5f) * 64.0f, float(i) + 0.5f, 1e-3f);
        EXPECT_NEAR((clip.y * 0.5f + 0.5f) * 64.0f, float(j) + 0.5f, 1e-3f);
        EXPECT_NEAR(v.depth_of(p), 1.5f, 1e-5f);
        EXPECT_NEAR((clip.z * 0.5f + 0.5f) * v.depth_range, 1.5f, 1e-5f);
      }
  }
}

// Every vertex of the scene, seen from every view, lands inside the image and inside the
// depth range: the views cover the scene's bounding sphere, nothing is clipped.
TEST(ViewSet, ViewsCoverTheSceneBoundingSphere) {
  for (const char* name : {"cornell", "atrium"}) {
    const Scene scene = load_scene(name);
    const BoundingSphere sphere = scene.bounding_sphere();
    for (const auto& p : scene.mesh.positions)
      ASSERT_LE(glm::length(p - sphere.centre), sphere.radius * (1 + 1e-6f));
    const ViewSet set = make_view_set(sphere, 32, 64);
    for (const auto& v : set.views) {
      for (const auto& p : scene.mesh.positions) {
        const glm::vec4 clip = v.view_projection * glm::vec4(p, 1.0f);
        EXPECT_LT(std::abs(clip.x), 1.0f);
        EXPECT_LT(std::abs(clip.y), 1.0f);
        EXPECT_LT(std::abs(clip.z), 1.0f);
      }
      // The sphere's extreme points along the view axes stay inside as well.
      for (const glm::vec3 axis : {v.right, v.up, v.forward}) {
        for (float sign : {-1.0f, 1.0f}) {
          const glm::vec4 clip =
              v.view_projection * glm::vec4(sphere.centre + sign * sphere.radius * axis, 1.0f);
          EXPECT_LE(std::max({std::abs(clip.x), std::abs(clip.y), std::abs(clip.z)}), 1.0f);
        }
      }
    }
  }
}

}  // namespace
}  // namespace ldm
