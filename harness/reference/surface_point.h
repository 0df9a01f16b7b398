#pragma once
// The surface points every reference renderer shades, found as the GPU's G-buffer pass
// finds them: the position interpolated from the hit triangle's vertices, the interpolated
// shading normal normalised and turned toward the viewer (the ray's origin), and the origin
// secondary rays start from, a few float ulps off the surface on the viewer's side.
#include <cstdint>
#include <optional>
#include <string>

#include <glm/glm.hpp>

#include "harness/reference/embree_scene.h"
#include "harness/reference/reference_image.h"
#include "harness/scene/camera.h"
#include "harness/scene/scene.h"

namespace ldm {

struct SurfacePoint {
  glm::vec3 position;          // interpolated like the rasteriser's v_position
  glm::vec3 shading_normal;    // unit, facing the viewer
  glm::vec3 geometric_normal;  // unit normal of the triangle's plane, on the viewer's side
  glm::vec3 offset_origin;     // where secondary rays start (ray_offset.h's rule)
  uint32_t triangle = 0;
};

// The point `hit` of the ray from `ray_origin` along `ray_direction`, seen from the origin.
SurfacePoint surface_point(const EmbreeScene& scene, const RayHit& hit, glm::vec3 ray_origin,
                           glm::vec3 ray_direction);
// The G-buffer point of pixel (x, y): the primary ray through its centre; nothing on a miss.
std::optional<SurfacePoint> camera_surface_point(const EmbreeScene& scene,
                                                 const CameraFrame& camera, int x, int y,
                                                 int width, int height);

// Secondary rays start this many float ulps of the hit triangle's largest coordinate off the
// surface (surface_point.cpp says why).
inline constexpr float kRayOffsetUlps = 64.0f;
// The largest such offset in a scene, in the coordinates it is traced in.
float max_ray_offset(const Scene& scene);
// Sets result.ray_offset to max_ray_offset(centred scene) and result.ray_offset_warning when
// it is a material fraction (> 1e-3) of the scene's radius or of `length_scale` (a length
// the reference resolves, e.g. AO's d_max; 0: none).
void annotate_ray_offset(ReferenceResult& result, const Scene& scene, double length_scale,
                         const std::string& length_scale_name);

}  // namespace ldm
