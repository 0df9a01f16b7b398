#pragma once
// The closed form of a tessellated integrating sphere (issue 20): the single-bounce indirect
// radiance that lighting_reference.h's `single_bounce` component estimates, computed for a
// closed convex mesh lit from inside by its spot light by deterministic quadrature over the
// mesh's own triangles. Inside a convex enclosure every surface point sees every other and
// the light sees them all, so with no visibility to test
//   L(x) = rho_x / pi * sum over triangles T of  integral_T L1(y) cos_x cos_y / |x - y|^2 dA_y
//   L1(y) = rho_y / pi * I(y - light) * cos_l / |y - light|^2
// with the triangles' own (face) normals: the geometry as tessellated, which the reference
// and the GPU pass render, not the sphere it approximates (for which L = rho^2 Phi /
// (4 pi^2 R^2) everywhere). The difference between the two is the tessellation's error.
//
// Quadrature: a triangle farther from x than kNearFactor times its diameter is split into
// parts of at most `part_size` times the mesh's radius around the light (halving its edges),
// each integrated by the 3-point rule of degree 2; a nearer one is split recursively until
// each part is that far from x (or kMaxDepth levels deep). Parts in x's own plane contribute nothing
// (cos_x = 0). Doubling the subdivision shows the rule's own error (the tests check it is
// far below the references' noise).
#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "harness/image/image.h"
#include "harness/scene/scene.h"

namespace ldm {

class ConvexSingleBounce {
 public:
  // Throws UserError (naming `context`) unless the mesh is closed and convex around the light:
  // every edge shared by exactly two triangles, each of which holds the other's far vertex and
  // the light on its inner side.
  explicit ConvexSingleBounce(const Scene& scene, double part_size = 1.0 / 32.0,
                              const std::string& context = "closed form");

  // Outgoing single-bounce radiance (RGB, W/(sr m^2)) at the surface point x of the mesh,
  // whose triangle has the unit normal n (either side: it is turned to the inside) and the
  // diffuse albedo `albedo`.
  glm::dvec3 radiance(const glm::dvec3& x, const glm::dvec3& n, const glm::dvec3& albedo) const;

  // For a mesh whose vertices all lie at one distance R from the light and whose triangles
  // share one grey albedo rho: rho^2 Phi / (4 pi^2 R^2), the ideal sphere's value (mean of
  // RGB); 0 when the mesh is not such a sphere.
  double ideal_sphere_radiance() const { return ideal_sphere_; }

  static constexpr double kNearFactor = 2.0;
  static constexpr int kMaxDepth = 9;

 private:
  struct Triangle {
    glm::dvec3 a, b, c, normal;  // normal: unit, toward the inside
    glm::dvec3 albedo;
  };
  struct Node {  // a far-field quadrature point
    glm::dvec3 position, normal, weighted;  // weighted: L1(y) * the rule's area weight
  };
  glm::dvec3 outgoing(const Triangle& t, const glm::dvec3& y) const;  // L1(y)
  void integrate_near(const Triangle& t, const glm::dvec3& a, const glm::dvec3& b,
                      const glm::dvec3& c, const glm::dvec3& x, const glm::dvec3& n, int depth,
                      glm::dvec3& sum) const;
  glm::dvec3 far_node_contribution(const Node& node, const glm::dvec3& x,
                                   const glm::dvec3& n) const;

  SpotLight light_;
  std::vector<Triangle> triangles_;
  std::vector<std::vector<Node>> nodes_;  // per triangle
  std::vector<double> sizes_;             // per triangle: its diameter
  std::vector<glm::dvec3> centroids_;
  double ideal_sphere_ = 0;
};

// The closed form per pixel for the scene's camera, at the surface points the references
// shade (surface_point.h: the primary hit through each pixel centre, in the scene's centred
// frame), RGB, 0 where the ray misses; `threads` 0: all cores.
Image convex_single_bounce_image(const Scene& scene, int width, int height,
                                 double part_size = 1.0 / 32.0, int threads = 0);

}  // namespace ldm
