#pragma once
// Appends flat-shaded primitives to a scene's triangle soup. Procedural scene generators are
// written with it; each primitive gets its own vertices so that normals are face normals.
#include <string>

#include <glm/glm.hpp>

#include "harness/scene/scene.h"

namespace ldm {

class MeshBuilder {
 public:
  explicit MeshBuilder(Scene& scene) : scene_(scene) {}

  // Returns the index of the material with this name, adding it if new.
  uint32_t material(const std::string& name, glm::vec3 albedo);

  // Counter-clockwise winding seen from the side the normal points to.
  void triangle(glm::vec3 a, glm::vec3 b, glm::vec3 c, uint32_t material);
  // Quad a-b-c-d (planar, counter-clockwise), split along a-c.
  void quad(glm::vec3 a, glm::vec3 b, glm::vec3 c, glm::vec3 d, uint32_t material);
  // Axis-aligned box with outward normals, optionally rotated about +y by yaw (radians)
  // around its centre.
  void box(glm::vec3 lo, glm::vec3 hi, uint32_t material, float yaw = 0.0f);
  // Closed prism around a vertical axis: `sides` faces, from y0 to y1, with caps.
  void cylinder(glm::vec3 base_centre, float radius, float height, int sides, uint32_t material);
  // Half-ring arch in the plane spanned by `along` (unit, horizontal) and +y, centred at
  // `centre` (the spring line's midpoint), extruded along `depth_dir` by `depth`.
  void arch(glm::vec3 centre, glm::vec3 along, glm::vec3 depth_dir, float inner_radius,
            float outer_radius, float depth, int segments, uint32_t material);
  // UV sphere.
  void sphere(glm::vec3 centre, float radius, int segments, uint32_t material);
  // A thin, zero-thickness sheet hanging from `top_left` to `top_right`, height `height`,
  // with `folds` sinusoidal folds of amplitude `amplitude` along `fold_dir`.
  void curtain(glm::vec3 top_left, glm::vec3 top_right, float height, glm::vec3 fold_dir,
               float amplitude, int folds, int columns, int rows, uint32_t material);

 private:
  Scene& scene_;
};

}  // namespace ldm
