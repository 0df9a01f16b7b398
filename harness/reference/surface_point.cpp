#include "harness/reference/surface_point.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

namespace ldm {
namespace {

float largest_magnitude(glm::vec3 p) {
  return std::max({std::abs(p.x), std::abs(p.y), std::abs(p.z)});
}

// A surface's offset is a material fraction of a length above this (the secondary rays'
// hit distances are biased by up to the offset; an occluder closer than it is missed).
constexpr double kMaterialOffsetFraction = 1e-3;

}  // namespace

// Why 64 ulps: x is interpolated from its triangle's vertices, so its error is a few ulps of
// their largest coordinate (and Embree's robust triangle test subtracts the ray origin from
// those same vertices); 64 ulps leave a margin of ~16x against self-intersection. The
// references trace scene-centred coordinates (centred_on_bounding_sphere), so these are ulps
// of the scene's extent, whatever its distance from the world origin: 64 * 2^-23 = 7.6e-6 of
// the radius at most.
float max_ray_offset(const Scene& scene) {
  float largest = 0.0f;
  for (const glm::vec3& p : scene.mesh.positions) largest = std::max(largest, largest_magnitude(p));
  return kRayOffsetUlps * std::numeric_limits<float>::epsilon() * largest;
}

SurfacePoint surface_point(const EmbreeScene& scene, const RayHit& hit, glm::vec3 ray_origin,
                           glm::vec3 ray_direction) {
  const TriangleMesh& mesh = scene.scene().mesh;
  const glm::uvec3 tri = mesh.triangles[hit.triangle];
  const glm::vec3 p0 = mesh.positions[tri.x], p1 = mesh.positions[tri.y],
                  p2 = mesh.positions[tri.z];
  SurfacePoint point;
  point.triangle = hit.triangle;
  // Interpolated like the rasteriser's v_position, and more exact than origin + t * direction.
  point.position = (1.0f - hit.u - hit.v) * p0 + hit.u * p1 + hit.v * p2;

  glm::vec3 geometric = glm::cross(p1 - p0, p2 - p0);
  geometric = glm::normalize(glm::dot(geometric, ray_direction) > 0.0f ? -geometric : geometric);
  point.geometric_normal = geometric;
  // As shaders/passes/gbuffer.frag: normalise, then face the viewer. A degenerate
  // interpolated normal (opposite vertex normals) falls back to the geometric one, not NaN.
  glm::vec3 n = scene.shading_normal(hit);
  const float length = glm::length(n);
  n = length > 1e-12f ? n / length : geometric;
  if (glm::dot(n, ray_origin - point.position) < 0.0f) n = -n;
  point.shading_normal = n;
  // Offset along the geometric normal on the side the viewer sees: that is the side of the
  // triangle's plane the secondary rays must start from, whatever the shading normal says.
  const float precision =
      std::max({largest_magnitude(p0), largest_magnitude(p1), largest_magnitude(p2)});
  point.offset_origin = point.position + kRayOffsetUlps *
                                             std::numeric_limits<float>::epsilon() * precision *
                                             geometric;
  return point;
}

std::optional<SurfacePoint> camera_surface_point(const EmbreeScene& scene,
                                                 const CameraFrame& camera, int x, int y,
                                                 int width, int height) {
  const glm::vec3 direction = camera.ray_direction(x, y, width, height);
  const auto hit =
      scene.intersect(camera.eye, direction, 0.0f, std::numeric_limits<float>::infinity());
  if (!hit) return std::nullopt;
  return surface_point(scene, *hit, camera.eye, direction);
}

void annotate_ray_offset(ReferenceResult& result, const Scene& scene, double length_scale,
                         const std::string& length_scale_name) {
  result.ray_offset = max_ray_offset(centred_on_bounding_sphere(scene));
  const double radius = scene.bounding_sphere().radius;
  std::string scale;
  if (length_scale > 0 && result.ray_offset > kMaterialOffsetFraction * length_scale)
    scale = length_scale_name;
  else if (result.ray_offset > kMaterialOffsetFraction * radius)
    scale = "the scene's radius";
  if (scale.empty()) return;
  char text[200];
  std::snprintf(text, sizeof text,
                "reference ray offset %g is a material fraction (> 1e-3) of %s: the reference "
                "may be biased",
                result.ray_offset, scale.c_str());
  result.ray_offset_warning = text;
}

}  // namespace ldm
