#pragma once
// The scene in an Embree 3 BVH, on the CPU: an oracle independent of OpenGL. Used for
// all-hits checks of the LDM structures and by the reference path tracer.
#include <cstdint>
#include <optional>
#include <vector>

#include <embree3/rtcore.h>
#include <glm/glm.hpp>

#include "harness/scene/scene.h"

namespace ldm {

struct RayHit {
  float t = 0;
  uint32_t triangle = 0;
  float u = 0, v = 0;  // barycentrics of vertices 1 and 2
};

class EmbreeScene {
 public:
  explicit EmbreeScene(const Scene& scene);
  ~EmbreeScene();
  EmbreeScene(const EmbreeScene&) = delete;
  EmbreeScene& operator=(const EmbreeScene&) = delete;

  std::optional<RayHit> intersect(glm::vec3 origin, glm::vec3 direction, float t_near,
                                  float t_far) const;
  bool occluded(glm::vec3 origin, glm::vec3 direction, float t_near, float t_far) const;
  // Every surface the ray crosses (each triangle once), nearest first.
  std::vector<RayHit> all_hit_records(glm::vec3 origin, glm::vec3 direction, float t_near,
                                      float t_far) const;
  // Just their distances.
  std::vector<float> all_hits(glm::vec3 origin, glm::vec3 direction, float t_near,
                              float t_far) const;

  // Unit normal of a triangle's plane.
  glm::vec3 geometric_normal(uint32_t triangle) const;
  // Interpolated shading normal at a hit (not normalised to face anything).
  glm::vec3 shading_normal(const RayHit& hit) const;
  const Scene& scene() const { return scene_; }
  RTCScene handle() const { return rtc_scene_; }

 private:
  const Scene& scene_;
  RTCDevice device_ = nullptr;
  RTCScene rtc_scene_ = nullptr;
};

}  // namespace ldm
