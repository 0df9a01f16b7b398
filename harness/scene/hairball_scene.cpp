// A procedural hairball, the thesis's second workload (§6.1.3, Table 5b): thousands of thin,
// curved, closed tubes inside a sphere. Every direction through it crosses many strands, so
// its depth complexity is high and even over the LDM (the opposite of the atrium's, which
// is low almost everywhere and deep along a few lines of sight), and a strand is a few LDM
// pixels wide at most. The size (radius), density (strands, their length and thickness) and
// shape (curl, tessellation) are parameters; the seed fixes the strands exactly.
#include <cmath>
#include <cstdint>

#include "harness/scene/generators.h"
#include "harness/scene/mesh_builder.h"
#include <numbers>

namespace ldm {
namespace {


// SplitMix64: a small, fully specified generator, so that a seed gives the same strands on
// every platform and library version (std::uniform_*_distribution does not promise that).
class StrandRandom {
 public:
  explicit StrandRandom(uint64_t seed) : state_(seed) {}
  float uniform() {  // [0, 1)
    return float(next() >> 40) * (1.0f / 16777216.0f);
  }
  glm::vec3 unit_vector() {
    const float z = 2.0f * uniform() - 1.0f, phi = 2.0f * std::numbers::pi_v<float> * uniform();
    const float s = std::sqrt(std::max(0.0f, 1.0f - z * z));
    return {s * std::cos(phi), s * std::sin(phi), z};
  }
  glm::vec3 in_ball(float radius) {  // uniform in the ball
    return unit_vector() * (radius * std::cbrt(uniform()));
  }

 private:
  uint64_t next() {
    uint64_t z = (state_ += 0x9e3779b97f4a7c15ull);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
  }
  uint64_t state_;
};

glm::vec3 rotate(glm::vec3 v, glm::vec3 axis, float angle) {  // Rodrigues, axis unit
  const float c = std::cos(angle), s = std::sin(angle);
  return v * c + glm::cross(axis, v) * s + axis * (glm::dot(axis, v) * (1.0f - c));
}

glm::vec3 any_perpendicular(glm::vec3 d) {
  const glm::vec3 other = std::abs(d.x) < 0.9f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0);
  return glm::normalize(glm::cross(d, other));
}

struct StrandShape {
  float ball_radius, tube_radius, length, curl;
  int segments, sides;
};

// One strand: a curve that turns about a slowly wandering axis and is reflected back at the
// sphere, swept by a `sides`-gon kept in a parallel-transported frame, capped at both ends.
void add_strand(MeshBuilder& b, StrandRandom& random, const StrandShape& s, uint32_t material) {
  glm::vec3 p = random.in_ball(0.85f * s.ball_radius);
  glm::vec3 d = random.unit_vector();
  glm::vec3 axis = any_perpendicular(d);
  const float step = s.length / float(s.segments);
  std::vector<glm::vec3> centres{p}, tangents{d};
  for (int i = 0; i < s.segments; ++i) {
    d = glm::normalize(rotate(d, axis, s.curl * step));
    // The turning axis wanders, so that strands curl in and out of plane like hair.
    const glm::vec3 w = random.unit_vector();
    axis = glm::normalize(axis + 0.6f * (w - glm::dot(w, d) * d));
    axis = glm::normalize(axis - glm::dot(axis, d) * d);
    p += d * step;
    if (const float r = glm::length(p); r > s.ball_radius) {  // back inside, reflected
      const glm::vec3 n = p / r;
      p = n * s.ball_radius;
      if (glm::dot(d, n) > 0.0f) d = glm::normalize(d - 2.0f * glm::dot(d, n) * n);
      axis = glm::normalize(axis - glm::dot(axis, d) * d);
    }
    centres.push_back(p);
    tangents.push_back(d);
  }
  // Rings in a parallel-transported frame (no twist between consecutive rings).
  std::vector<std::vector<glm::vec3>> rings;
  glm::vec3 u = any_perpendicular(tangents[0]);
  for (size_t i = 0; i < centres.size(); ++i) {
    const glm::vec3 t = tangents[i];
    u = glm::normalize(u - glm::dot(u, t) * t);
    const glm::vec3 v = glm::cross(t, u);
    std::vector<glm::vec3> ring;
    for (int k = 0; k < s.sides; ++k) {
      const float a = 2.0f * std::numbers::pi_v<float> * float(k) / float(s.sides);
      ring.push_back(centres[i] + s.tube_radius * (std::cos(a) * u + std::sin(a) * v));
    }
    rings.push_back(std::move(ring));
  }
  for (size_t i = 0; i + 1 < rings.size(); ++i)
    for (int k = 0; k < s.sides; ++k) {
      const int k1 = (k + 1) % s.sides;
      b.quad(rings[i][k], rings[i][k1], rings[i + 1][k1], rings[i + 1][k], material);
    }
  for (int k = 1; k + 1 < s.sides; ++k) {
    b.triangle(rings.front()[0], rings.front()[k + 1], rings.front()[k], material);
    b.triangle(rings.back()[0], rings.back()[k], rings.back()[k + 1], material);
  }
}

}  // namespace

Scene make_hairball_scene(GeneratorParams& params) {
  const float radius = params.number("radius", 1.0f, 1e-3f, 1e6f);
  StrandShape shape;
  shape.ball_radius = radius;
  const int strands = params.integer("strands", 1200, 1, 200000);
  shape.tube_radius = params.number("strand_radius", 0.006f * radius, 1e-6f * radius, 0.2f * radius);
  shape.length = params.number("strand_length", 2.5f * radius, 1e-3f * radius, 100.0f * radius);
  shape.curl = params.number("curl", 3.0f / radius, 0.0f, 1e3f / radius);
  shape.segments = params.integer("segments", 14, 1, 1024);
  shape.sides = params.integer("sides", 3, 3, 32);
  const int seed = params.integer("seed", 1, 0, 1 << 30);

  Scene scene;
  scene.name = "hairball";
  MeshBuilder b(scene);
  const uint32_t hair = b.material("hair", {0.55f, 0.45f, 0.35f});
  StrandRandom random(uint64_t(seed) * 0x2545f4914f6cdd1dull + 1);
  for (int i = 0; i < strands; ++i) add_strand(b, random, shape, hair);

  // Framed like a mesh file (scene_defaults.h), a little closer: the ball fills the view.
  scene.camera.target = {0, 0, 0};
  scene.camera.eye = glm::vec3(0.3f, 0.25f, 1.0f) * (2.9f * radius);
  scene.camera.up = {0, 1, 0};
  scene.camera.fov_y_deg = 40.0f;
  scene.light.position = {0.5f * radius, 2.5f * radius, 0.8f * radius};
  scene.light.direction = glm::normalize(-scene.light.position);
  scene.light.inner_angle_deg = 20.0f;
  scene.light.outer_angle_deg = 28.0f;
  scene.light.intensity = glm::vec3(params.number("light_intensity", 7.0f * radius * radius, 0.0f, 1e12f));
  scene.ao.attenuated = true;
  scene.ao.d_max = params.number("d_max", 0.25f * radius, 1e-6f * radius, 1e6f);
  return scene;
}

}  // namespace ldm
