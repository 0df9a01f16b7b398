#include "harness/reference/ao_estimator.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <string>

#include "harness/reference/hemisphere.h"
#include "harness/util/error.h"

namespace ldm {
namespace {

// Secondary rays start this many float ulps of the hit's coordinates off the surface. x is
// interpolated from its triangle's vertices, so its error is a few ulps of their largest
// coordinate (and Embree's robust triangle test subtracts the ray origin from those same
// vertices); 64 ulps leave a margin of ~16x against self-intersection. The tracer works in
// coordinates centred on the scene (ao_reference.cpp), so these ulps are ulps of the scene's
// extent, whatever its distance from the world origin: 64 * 2^-23 = 7.6e-6 of the radius at
// most. (Before, the offset was 1e-5 of |centre| + radius: 17 units for a unit scene
// translated 1e6 from the origin, past every occluder.)
constexpr float kRayOffsetUlps = 64.0f;
// Secondary rays go to Embree as streams of this many (rtcIntersect1M / rtcOccluded1M).
// Measured on Cornell and atrium, 128x128, 1 thread: streams trace 1.2x (intersect) and
// 1.6x (occluded) the rays per CPU-second of one rtcIntersect1/rtcOccluded1 call per ray;
// 8- and 16-wide packets gain as much for intersect but less for occluded.
constexpr uint32_t kBatchSize = 64;

void validate(const AoSettings& ao) {
  if (!(ao.d_max > 0.0f) || !std::isfinite(ao.d_max))
    throw UserError("ao.d_max must be positive and finite (got " + std::to_string(ao.d_max) + ")");
  if (!(ao.falloff_exponent >= 0.0f) || !std::isfinite(ao.falloff_exponent))
    throw UserError("ao.falloff_exponent must be non-negative and finite (got " +
                    std::to_string(ao.falloff_exponent) + ")");
}

float largest_magnitude(glm::vec3 p) {
  return std::max({std::abs(p.x), std::abs(p.y), std::abs(p.z)});
}

RTCRay make_ray(glm::vec3 origin, glm::vec3 direction, float t_far) {
  RTCRay r;
  r.org_x = origin.x;
  r.org_y = origin.y;
  r.org_z = origin.z;
  r.tnear = 0.0f;
  r.dir_x = direction.x;
  r.dir_y = direction.y;
  r.dir_z = direction.z;
  r.time = 0.0f;
  r.tfar = t_far;
  r.mask = 0xFFFFFFFFu;
  r.id = 0;
  r.flags = 0;
  return r;
}

}  // namespace

float AoEstimator::max_ray_offset(const Scene& scene) {
  float largest = 0.0f;
  for (const glm::vec3& p : scene.mesh.positions) largest = std::max(largest, largest_magnitude(p));
  return kRayOffsetUlps * std::numeric_limits<float>::epsilon() * largest;
}

AoEstimator::AoEstimator(const EmbreeScene& scene, const AoSettings& ao, int width, int height)
    : scene_(scene),
      ao_(ao),
      width_(width),
      height_(height),
      camera_(camera_frame(scene.scene().camera, width, height)),
      ray_offset_(max_ray_offset(scene.scene())) {
  validate(ao);
  if (width <= 0 || height <= 0) throw UserError("AO reference: image size must be positive");
}

bool AoEstimator::primary_hit(int x, int y, SurfacePoint* point) const {
  const glm::vec3 direction = camera_.ray_direction(x, y, width_, height_);
  const auto hit = scene_.intersect(camera_.eye, direction, 0.0f,
                                    std::numeric_limits<float>::infinity());
  if (!hit) return false;
  const TriangleMesh& mesh = scene_.scene().mesh;
  const glm::uvec3 tri = mesh.triangles[hit->triangle];
  const glm::vec3 p0 = mesh.positions[tri.x], p1 = mesh.positions[tri.y],
                  p2 = mesh.positions[tri.z];
  // Interpolated like the rasteriser's v_position, and more exact than eye + t * direction.
  point->position = (1.0f - hit->u - hit->v) * p0 + hit->u * p1 + hit->v * p2;

  glm::vec3 geometric = glm::cross(p1 - p0, p2 - p0);
  geometric = glm::normalize(glm::dot(geometric, direction) > 0.0f ? -geometric : geometric);
  // As shaders/passes/gbuffer.frag: normalise, then face the eye. A degenerate interpolated
  // normal (opposite vertex normals) falls back to the geometric one instead of NaN.
  glm::vec3 n = scene_.shading_normal(*hit);
  const float length = glm::length(n);
  n = length > 1e-12f ? n / length : geometric;
  if (glm::dot(n, camera_.eye - point->position) < 0.0f) n = -n;
  point->shading_normal = n;
  // Offset along the geometric normal on the side the camera sees: that is the side of the
  // triangle's plane the secondary rays must start from, whatever the shading normal says.
  const float precision =
      std::max({largest_magnitude(p0), largest_magnitude(p1), largest_magnitude(p2)});
  point->offset_origin =
      point->position + kRayOffsetUlps * std::numeric_limits<float>::epsilon() * precision * geometric;
  return true;
}

float AoEstimator::attenuated_visibility(float hit_distance) const {
  const float ratio = std::min(hit_distance / ao_.d_max, 1.0f);
  return ao_.falloff_exponent == 2.0f ? ratio * ratio : std::pow(ratio, ao_.falloff_exponent);
}

void AoEstimator::trace_visibility(glm::vec3 origin, const glm::vec3* directions, uint32_t count,
                                   float* visibility) const {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);  // incoherent: measured fastest for these rays
  if (ao_.attenuated) {
    // Attenuated rays only need to reach d_max: anything farther has V = 1, like a miss.
    std::array<RTCRayHit, kBatchSize> rays;
    for (uint32_t i = 0; i < count; ++i) {
      rays[i].ray = make_ray(origin, directions[i], ao_.d_max);
      rays[i].hit.geomID = RTC_INVALID_GEOMETRY_ID;
    }
    rtcIntersect1M(scene_.handle(), &context, rays.data(), count, sizeof(RTCRayHit));
    for (uint32_t i = 0; i < count; ++i)
      visibility[i] = rays[i].hit.geomID == RTC_INVALID_GEOMETRY_ID
                          ? 1.0f
                          : attenuated_visibility(rays[i].ray.tfar);
  } else {
    std::array<RTCRay, kBatchSize> rays;
    for (uint32_t i = 0; i < count; ++i)
      rays[i] = make_ray(origin, directions[i], std::numeric_limits<float>::infinity());
    rtcOccluded1M(scene_.handle(), &context, rays.data(), count, sizeof(RTCRay));
    for (uint32_t i = 0; i < count; ++i)
      visibility[i] = rays[i].tfar < 0.0f ? 0.0f : 1.0f;  // Embree sets tfar = -inf on a hit
  }
}

double AoEstimator::visibility_sum(const SurfacePoint& point, uint32_t count, Pcg32& rng) const {
  const NormalFrame frame(point.shading_normal);
  std::array<glm::vec3, kBatchSize> directions;
  std::array<float, kBatchSize> visibility;
  double sum = 0.0;
  for (uint32_t done = 0; done < count; done += kBatchSize) {
    const uint32_t n = std::min(kBatchSize, count - done);
    for (uint32_t i = 0; i < n; ++i) {
      const float u1 = rng.next_float(), u2 = rng.next_float();
      directions[i] = frame.to_world(cosine_weighted_direction(u1, u2));
    }
    trace_visibility(point.offset_origin, directions.data(), n, visibility.data());
    for (uint32_t i = 0; i < n; ++i) sum += visibility[i];
  }
  return sum;
}

float AoEstimator::pixel_mean(int x, int y, uint32_t spp, Pcg32& rng) const {
  SurfacePoint point;
  if (!primary_hit(x, y, &point)) return 0.0f;
  return float(visibility_sum(point, spp, rng) / double(spp));
}

}  // namespace ldm
