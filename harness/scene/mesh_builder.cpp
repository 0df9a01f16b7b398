#include "harness/scene/mesh_builder.h"

#include <cmath>
#include <numbers>

namespace ldm {
namespace {
}

uint32_t MeshBuilder::material(const std::string& name, glm::vec3 albedo) {
  for (uint32_t i = 0; i < scene_.materials.size(); ++i)
    if (scene_.materials[i].name == name) return i;
  scene_.materials.push_back(Material{name, albedo});
  return uint32_t(scene_.materials.size() - 1);
}

void MeshBuilder::triangle(glm::vec3 a, glm::vec3 b, glm::vec3 c, uint32_t material) {
  glm::vec3 n = glm::cross(b - a, c - a);
  const float length = glm::length(n);
  if (!(length > 0.0f)) return;  // degenerate: rasterises to nothing anyway
  n /= length;
  auto& mesh = scene_.mesh;
  const auto base = uint32_t(mesh.positions.size());
  mesh.positions.insert(mesh.positions.end(), {a, b, c});
  mesh.normals.insert(mesh.normals.end(), {n, n, n});
  mesh.triangles.emplace_back(base, base + 1, base + 2);
  mesh.triangle_materials.push_back(material);
}

void MeshBuilder::quad(glm::vec3 a, glm::vec3 b, glm::vec3 c, glm::vec3 d, uint32_t material) {
  triangle(a, b, c, material);
  triangle(a, c, d, material);
}

void MeshBuilder::box(glm::vec3 lo, glm::vec3 hi, uint32_t material, float yaw) {
  const glm::vec3 centre = 0.5f * (lo + hi);
  const float c = std::cos(yaw), s = std::sin(yaw);
  auto corner = [&](int i) {
    glm::vec3 p((i & 1) ? hi.x : lo.x, (i & 2) ? hi.y : lo.y, (i & 4) ? hi.z : lo.z);
    glm::vec3 d = p - centre;
    return centre + glm::vec3(c * d.x + s * d.z, d.y, -s * d.x + c * d.z);
  };
  // Faces listed counter-clockwise seen from outside.
  quad(corner(0), corner(4), corner(6), corner(2), material);  // -x
  quad(corner(1), corner(3), corner(7), corner(5), material);  // +x
  quad(corner(0), corner(1), corner(5), corner(4), material);  // -y
  quad(corner(2), corner(6), corner(7), corner(3), material);  // +y
  quad(corner(0), corner(2), corner(3), corner(1), material);  // -z
  quad(corner(4), corner(5), corner(7), corner(6), material);  // +z
}

void MeshBuilder::cylinder(glm::vec3 base, float radius, float height, int sides,
                           uint32_t material) {
  const glm::vec3 top = base + glm::vec3(0, height, 0);
  for (int i = 0; i < sides; ++i) {
    const float a0 = 2 * std::numbers::pi_v<float> * float(i) / float(sides);
    const float a1 = 2 * std::numbers::pi_v<float> * float(i + 1) / float(sides);
    const glm::vec3 r0(radius * std::cos(a0), 0, -radius * std::sin(a0));
    const glm::vec3 r1(radius * std::cos(a1), 0, -radius * std::sin(a1));
    quad(base + r0, base + r1, top + r1, top + r0, material);
    triangle(top, top + r0, top + r1, material);
    triangle(base, base + r1, base + r0, material);
  }
}

void MeshBuilder::arch(glm::vec3 centre, glm::vec3 along, glm::vec3 depth_dir, float inner_radius,
                       float outer_radius, float depth, int segments, uint32_t material) {
  const glm::vec3 up(0, 1, 0);
  const glm::vec3 back = depth_dir * depth;
  auto ring = [&](float radius, int i) {
    const float a = std::numbers::pi_v<float> * float(i) / float(segments);
    return centre + radius * (std::cos(a) * along + std::sin(a) * up);
  };
  // Orientation: the front face's normal must point to -depth_dir.
  const bool flip = glm::dot(glm::cross(along, up), depth_dir) > 0.0f;
  auto oriented_quad = [&](glm::vec3 a, glm::vec3 b, glm::vec3 c, glm::vec3 d, bool reverse) {
    if (reverse)
      quad(a, d, c, b, material);
    else
      quad(a, b, c, d, material);
  };
  for (int i = 0; i < segments; ++i) {
    const glm::vec3 i0 = ring(inner_radius, i), i1 = ring(inner_radius, i + 1);
    const glm::vec3 o0 = ring(outer_radius, i), o1 = ring(outer_radius, i + 1);
    oriented_quad(i0, o0, o1, i1, flip);                                // front face
    oriented_quad(i0 + back, i1 + back, o1 + back, o0 + back, flip);    // back face
    oriented_quad(o0, o0 + back, o1 + back, o1, flip);                  // outer surface
    oriented_quad(i0, i1, i1 + back, i0 + back, flip);                  // intrados
  }
}

void MeshBuilder::sphere(glm::vec3 centre, float radius, int segments, uint32_t material) {
  const int rings = std::max(2, segments / 2);
  auto point = [&](int ring, int seg) {
    const float theta = std::numbers::pi_v<float> * float(ring) / float(rings);
    const float phi = 2 * std::numbers::pi_v<float> * float(seg) / float(segments);
    return centre + radius * glm::vec3(std::sin(theta) * std::cos(phi), std::cos(theta),
                                       -std::sin(theta) * std::sin(phi));
  };
  for (int r = 0; r < rings; ++r)
    for (int s = 0; s < segments; ++s) {
      const glm::vec3 a = point(r, s), b = point(r + 1, s), c = point(r + 1, s + 1),
                      d = point(r, s + 1);
      if (r > 0) triangle(a, b, d, material);
      if (r < rings - 1) triangle(b, c, d, material);
    }
}

void MeshBuilder::curtain(glm::vec3 top_left, glm::vec3 top_right, float height,
                          glm::vec3 fold_dir, float amplitude, int folds, int columns, int rows,
                          uint32_t material) {
  auto point = [&](int col, int row) {
    const float u = float(col) / float(columns);
    const float v = float(row) / float(rows);
    const glm::vec3 along = glm::mix(top_left, top_right, u);
    const float fold = amplitude * std::sin(2 * std::numbers::pi_v<float> * float(folds) * u);
    return along + fold * fold_dir - glm::vec3(0, v * height, 0);
  };
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < columns; ++c)
      quad(point(c, r), point(c, r + 1), point(c + 1, r + 1), point(c + 1, r), material);
}

}  // namespace ldm
