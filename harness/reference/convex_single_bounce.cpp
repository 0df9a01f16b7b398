#include "harness/reference/convex_single_bounce.h"

#include <cmath>
#include <map>
#include <numbers>
#include <tuple>
#include <unordered_map>

#include <glm/gtc/type_precision.hpp>

#include <algorithm>
#include <atomic>
#include <thread>

#include "harness/reference/embree_scene.h"
#include "harness/reference/surface_point.h"
#include "harness/scene/camera.h"
#include "harness/scene/spot_light.h"
#include "harness/util/error.h"

namespace ldm {
namespace {

constexpr double kPi = std::numbers::pi;

double diameter(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c) {
  return std::max({glm::length(b - a), glm::length(c - b), glm::length(a - c)});
}

// The 3-point rule of degree 2 on a triangle: the points (2/3, 1/6, 1/6) and permutations in
// barycentric coordinates, a third of the area each.
template <typename F>
void three_point_rule(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c, F&& f) {
  const double third_area = glm::length(glm::cross(b - a, c - a)) / 6.0;
  f((4.0 * a + b + c) / 6.0, third_area);
  f((a + 4.0 * b + c) / 6.0, third_area);
  f((a + b + 4.0 * c) / 6.0, third_area);
}

// Splits (a, b, c) into 4^levels parts by its edges' midpoints.
template <typename F>
void split(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c, int levels, F&& f) {
  if (levels == 0) return f(a, b, c);
  const glm::dvec3 ab = 0.5 * (a + b), bc = 0.5 * (b + c), ca = 0.5 * (c + a);
  split(a, ab, ca, levels - 1, f);
  split(ab, b, bc, levels - 1, f);
  split(ca, bc, c, levels - 1, f);
  split(ab, bc, ca, levels - 1, f);
}

// Vertices of one position, up to float rounding (a generator's seam and poles repeat a
// point computed twice), as one vertex: within `tolerance` of the first one seen.
class VertexWelder {
 public:
  explicit VertexWelder(double tolerance) : cell_(tolerance), tolerance_(tolerance) {}
  uint32_t id(const glm::dvec3& p) {
    const glm::i64vec3 c(std::floor(p.x / cell_), std::floor(p.y / cell_), std::floor(p.z / cell_));
    for (int dx = -1; dx <= 1; ++dx)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dz = -1; dz <= 1; ++dz) {
          const auto found = cells_.find(glm::i64vec3(c.x + dx, c.y + dy, c.z + dz));
          if (found == cells_.end()) continue;
          for (uint32_t i : found->second)
            if (glm::length(points_[i] - p) <= tolerance_) return i;
        }
    points_.push_back(p);
    cells_[c].push_back(uint32_t(points_.size() - 1));
    return uint32_t(points_.size() - 1);
  }

 private:
  struct Hash {
    size_t operator()(const glm::i64vec3& c) const {
      return size_t(c.x * 73856093) ^ size_t(c.y * 19349663) ^ size_t(c.z * 83492791);
    }
  };
  double cell_, tolerance_;
  std::vector<glm::dvec3> points_;
  std::unordered_map<glm::i64vec3, std::vector<uint32_t>, Hash> cells_;
};

}  // namespace

ConvexSingleBounce::ConvexSingleBounce(const Scene& scene, double part_size, const std::string& context)
    : light_(scene.light) {
  const TriangleMesh& mesh = scene.mesh;
  if (mesh.triangles.empty()) throw UserError(context + ": the scene has no triangles");
  const glm::dvec3 light(scene.light.position);
  // Edges by their end points (vertices of one position, up to 1e-6 of the mesh's extent,
  // are one vertex): each must be shared by exactly two triangles, each holding the other's
  // far vertex on its inner side.
  double extent = 0;
  for (const glm::vec3& p : mesh.positions) extent = std::max(extent, double(glm::length(p - scene.light.position)));
  VertexWelder welder(1e-6 * extent);
  std::map<std::pair<uint32_t, uint32_t>, std::vector<std::pair<uint32_t, uint32_t>>> edges;
  for (uint32_t t = 0; t < mesh.triangles.size(); ++t) {
    const glm::uvec3 tri = mesh.triangles[t];
    for (int e = 0; e < 3; ++e) {
      uint32_t u = welder.id(glm::dvec3(mesh.positions[tri[e]]));
      uint32_t v = welder.id(glm::dvec3(mesh.positions[tri[(e + 1) % 3]]));
      if (u == v) throw UserError(context + ": triangle " + std::to_string(t) + " has a collapsed edge");
      if (v < u) std::swap(u, v);
      edges[{u, v}].push_back({t, tri[(e + 2) % 3]});
    }
  }
  double radius_min = INFINITY, radius_max = 0;
  for (uint32_t t = 0; t < mesh.triangles.size(); ++t) {
    const glm::uvec3 tri = mesh.triangles[t];
    Triangle T;
    T.a = glm::dvec3(mesh.positions[tri.x]);
    T.b = glm::dvec3(mesh.positions[tri.y]);
    T.c = glm::dvec3(mesh.positions[tri.z]);
    const glm::dvec3 cross = glm::cross(T.b - T.a, T.c - T.a);
    if (!(glm::length(cross) > 0.0))
      throw UserError(context + ": triangle " + std::to_string(t) + " has zero area");
    T.normal = glm::normalize(cross);
    if (glm::dot(T.normal, light - T.a) < 0.0) T.normal = -T.normal;
    if (!(glm::dot(T.normal, light - T.a) > 0.0))
      throw UserError(context + ": the light lies in the plane of triangle " + std::to_string(t) +
                      ": not inside a convex enclosure");
    T.albedo = glm::dvec3(scene.materials.at(mesh.triangle_materials.at(t)).albedo);
    triangles_.push_back(T);
    for (const auto& p : {T.a, T.b, T.c}) {
      radius_min = std::min(radius_min, glm::length(p - light));
      radius_max = std::max(radius_max, glm::length(p - light));
    }
  }
  const double scale = radius_max;
  for (const auto& [edge, sides] : edges) {
    if (sides.size() != 2)
      throw UserError(context + ": an edge is shared by " + std::to_string(sides.size()) +
                      " triangles: the mesh is not a closed surface");
    for (int k = 0; k < 2; ++k) {
      const Triangle& T = triangles_[sides[k].first];
      const glm::dvec3 far(mesh.positions[sides[1 - k].second]);
      if (glm::dot(T.normal, far - T.a) < -1e-6 * scale)
        throw UserError(context + ": the mesh is not convex around the light (triangle " +
                        std::to_string(sides[k].first) + ")");
    }
  }
  // The far-field nodes.
  nodes_.resize(triangles_.size());
  sizes_.resize(triangles_.size());
  centroids_.resize(triangles_.size());
  for (size_t t = 0; t < triangles_.size(); ++t) {
    const Triangle& T = triangles_[t];
    centroids_[t] = (T.a + T.b + T.c) / 3.0;
    sizes_[t] = diameter(T.a, T.b, T.c);
    int levels = 0;
    while (levels < kMaxDepth && sizes_[t] / double(1 << levels) > part_size * scale) ++levels;
    split(T.a, T.b, T.c, levels, [&](const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c) {
      three_point_rule(a, b, c, [&](const glm::dvec3& y, double weight) {
        nodes_[t].push_back({y, T.normal, outgoing(T, y) * weight});
      });
    });
  }
  // The ideal sphere's value, where the mesh is one (every vertex at one distance, one grey).
  bool grey = true;
  for (const Triangle& T : triangles_)
    grey = grey && T.albedo == triangles_[0].albedo && T.albedo.x == T.albedo.y && T.albedo.y == T.albedo.z;
  if (grey && radius_max - radius_min <= 1e-5 * radius_max) {
    const double rho = triangles_[0].albedo.x, flux = spot_radiant_flux(scene.light).x;
    const double r = 0.5 * (radius_min + radius_max);
    ideal_sphere_ = rho * rho * flux / (4.0 * kPi * kPi * r * r);
  }
}

glm::dvec3 ConvexSingleBounce::outgoing(const Triangle& t, const glm::dvec3& y) const {
  const glm::dvec3 from_light = y - glm::dvec3(light_.position);
  const double r2 = glm::dot(from_light, from_light);
  const glm::dvec3 w = from_light / std::sqrt(r2);
  const double cos_l = -glm::dot(t.normal, w);
  if (!(cos_l > 0.0)) return glm::dvec3(0.0);
  const glm::dvec3 intensity(spot_radiant_intensity(light_, glm::vec3(w)));
  return t.albedo / kPi * intensity * cos_l / r2;
}

glm::dvec3 ConvexSingleBounce::far_node_contribution(const Node& node, const glm::dvec3& x,
                                                     const glm::dvec3& n) const {
  const glm::dvec3 to = node.position - x;
  const double d2 = glm::dot(to, to);
  const double cos_x = glm::dot(n, to), cos_y = -glm::dot(node.normal, to);
  if (!(cos_x > 0.0) || !(cos_y > 0.0)) return glm::dvec3(0.0);
  return node.weighted * (cos_x * cos_y / (d2 * d2));
}

void ConvexSingleBounce::integrate_near(const Triangle& t, const glm::dvec3& a, const glm::dvec3& b,
                                        const glm::dvec3& c, const glm::dvec3& x,
                                        const glm::dvec3& n, int depth, glm::dvec3& sum) const {
  const glm::dvec3 centroid = (a + b + c) / 3.0;
  if (depth < kMaxDepth && glm::length(centroid - x) < kNearFactor * diameter(a, b, c)) {
    const glm::dvec3 ab = 0.5 * (a + b), bc = 0.5 * (b + c), ca = 0.5 * (c + a);
    integrate_near(t, a, ab, ca, x, n, depth + 1, sum);
    integrate_near(t, ab, b, bc, x, n, depth + 1, sum);
    integrate_near(t, ca, bc, c, x, n, depth + 1, sum);
    integrate_near(t, ab, bc, ca, x, n, depth + 1, sum);
    return;
  }
  three_point_rule(a, b, c, [&](const glm::dvec3& y, double weight) {
    sum += far_node_contribution({y, t.normal, outgoing(t, y) * weight}, x, n);
  });
}

glm::dvec3 ConvexSingleBounce::radiance(const glm::dvec3& x, const glm::dvec3& n_in,
                                        const glm::dvec3& albedo) const {
  glm::dvec3 n = glm::normalize(n_in);
  if (glm::dot(n, glm::dvec3(light_.position) - x) < 0.0) n = -n;
  glm::dvec3 sum(0.0);
  for (size_t i = 0; i < triangles_.size(); ++i) {
    const Triangle& T = triangles_[i];
    // x's own plane: cos_x = 0 over it.
    const double size = sizes_[i];
    if (std::abs(glm::dot(n, T.a - x)) <= 1e-5 * size && std::abs(glm::dot(n, T.b - x)) <= 1e-5 * size &&
        std::abs(glm::dot(n, T.c - x)) <= 1e-5 * size)
      continue;
    if (glm::length(centroids_[i] - x) >= kNearFactor * size) {
      for (const Node& node : nodes_[i]) sum += far_node_contribution(node, x, n);
    } else {
      integrate_near(T, T.a, T.b, T.c, x, n, 0, sum);
    }
  }
  return albedo / kPi * sum;
}

Image convex_single_bounce_image(const Scene& scene, int width, int height, double part_size,
                                 int threads) {
  const Scene centred = centred_on_bounding_sphere(scene);
  const ConvexSingleBounce closed(centred, part_size);
  const EmbreeScene embree(centred);
  const CameraFrame camera = camera_frame(centred.camera, width, height);
  Image image;
  image.width = width;
  image.height = height;
  image.channels = 3;
  image.pixels.assign(size_t(width) * height * 3, 0.0f);
  std::atomic<int> next_row{0};
  auto work = [&] {
    for (int y; (y = next_row++) < height;)
      for (int x = 0; x < width; ++x) {
        const auto point = camera_surface_point(embree, camera, x, y, width, height);
        if (!point) continue;
        const glm::dvec3 albedo(
            centred.materials.at(centred.mesh.triangle_materials.at(point->triangle)).albedo);
        const glm::dvec3 l = closed.radiance(glm::dvec3(point->position),
                                             glm::dvec3(point->geometric_normal), albedo);
        for (int c = 0; c < 3; ++c) image.at(x, y, c) = float(l[c]);
      }
  };
  const int count = threads > 0 ? threads : int(std::max(1u, std::thread::hardware_concurrency()));
  std::vector<std::thread> pool;
  for (int i = 1; i < count; ++i) pool.emplace_back(work);
  work();
  for (auto& t : pool) t.join();
  return image;
}

}  // namespace ldm
