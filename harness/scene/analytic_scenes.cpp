// Scenes whose ambient occlusion has a closed form (tests/ao derive and check them). Planes
// are large compared with d_max so that, with attenuated visibility, they act as infinite.
// Each generator reads its parameters, builds its geometry and places its camera and light:
// alike in form, different scenes (what they share is floor_square, read_ao, set_camera).
#include "harness/scene/generators.h"
#include "harness/scene/mesh_builder.h"

#include <cmath>

namespace ldm {
namespace {

void floor_square(MeshBuilder& b, float half, float y, uint32_t material) {
  b.quad({-half, y, half}, {half, y, half}, {half, y, -half}, {-half, y, -half}, material);
}

void read_generator_ao(GeneratorParams& params, Scene& scene, float default_d_max) {
  scene.ao.attenuated = params.boolean("attenuated", true);
  scene.ao.d_max = params.number("d_max", default_d_max, 1e-6f, 1e6f);
  scene.ao.normal_offset_pixels = params.number("normal_offset", 0.0f, 0.0f, 100.0f);
}

// The analytic scenes' cameras: from `eye` toward `target` with -z up in the image (the
// scenes lie along x and z, seen from above), fov_y degrees.
void set_camera(Scene& scene, glm::vec3 eye, glm::vec3 target, float fov_y_deg) {
  scene.camera.eye = eye;
  scene.camera.target = target;
  scene.camera.up = {0.0f, 0.0f, -1.0f};
  scene.camera.fov_y_deg = fov_y_deg;
}

}  // namespace

Scene make_plane_scene(GeneratorParams& params) {
  Scene scene;
  scene.name = "plane";
  const float half = params.number("half_size", 4.0f, 1e-3f, 1e6f);
  MeshBuilder b(scene);
  floor_square(b, half, 0.0f, b.material("grey", glm::vec3(0.5f)));
  set_camera(scene, {0.0f, 1.0f, 0.0f}, {0.0f, 0.0f, 0.0f}, 60.0f);
  scene.light.position = {0.0f, 3.0f, 0.0f};
  read_generator_ao(params, scene, 1.0f);
  return scene;
}

Scene make_parallel_planes_scene(GeneratorParams& params) {
  Scene scene;
  scene.name = "parallel-planes";
  const float h = params.number("h", 1.0f, 1e-3f, 1e6f);
  const float half = params.number("half_size", 4.0f, 1e-3f, 1e6f);
  MeshBuilder b(scene);
  const uint32_t grey = b.material("grey", glm::vec3(0.5f));
  floor_square(b, half, 0.0f, grey);
  // The ceiling faces down, into the gap.
  b.quad({-half, h, -half}, {half, h, -half}, {half, h, half}, {-half, h, half}, grey);
  // The camera hangs just under the ceiling and looks straight down at the floor.
  set_camera(scene, {0.0f, 0.9f * h, 0.0f}, {0.0f, 0.0f, 0.0f}, 60.0f);
  scene.light.position = {0.0f, 0.8f * h, 0.0f};
  read_generator_ao(params, scene, 2.0f * h);
  return scene;
}

Scene make_wall_scene(GeneratorParams& params) {
  Scene scene;
  scene.name = "wall";
  const float half = params.number("half_size", 4.0f, 1e-3f, 1e6f);
  const float height = params.number("height", 4.0f, 1e-3f, 1e6f);
  MeshBuilder b(scene);
  const uint32_t grey = b.material("grey", glm::vec3(0.5f));
  // Floor on x >= 0 only, meeting the wall x = 0 (normal +x) along the z axis.
  b.quad({0.0f, 0.0f, half}, {half, 0.0f, half}, {half, 0.0f, -half}, {0.0f, 0.0f, -half}, grey);
  b.quad({0.0f, 0.0f, -half}, {0.0f, height, -half}, {0.0f, height, half}, {0.0f, 0.0f, half},
         grey);
  // Looking straight down at the strip 0 < x < 1 next to the wall.
  set_camera(scene, {0.6f, 1.2f, 0.0f}, {0.6f, 0.0f, 0.0f}, 50.0f);
  scene.light.position = {1.0f, 3.0f, 0.0f};
  read_generator_ao(params, scene, 1.0f);
  return scene;
}

}  // namespace ldm

namespace ldm {

// A spot light shining straight down on a floor (x >= 0) beside a perpendicular wall (the
// plane x = 0, normal +x). The light stands at least h tan(outer) from the wall, so its cone
// never reaches the wall: the wall is lit by the floor's diffuse reflection alone, and its
// single-bounce indirect light is one integral over the lit disc of the floor (tests/reference
// integrates it), while the floor receives no single-bounce light at all.
Scene make_spot_bounce_scene(GeneratorParams& params) {
  Scene scene;
  scene.name = "spot-bounce";
  const float half = params.number("half_size", 4.0f, 1e-3f, 1e6f);
  const float height = params.number("height", 4.0f, 1e-3f, 1e6f);
  const float light_height = params.number("light_height", 1.0f, 1e-3f, 1e6f);
  constexpr float kInnerDeg = 30.0f, kOuterDeg = 45.0f;
  const float reach = light_height * std::tan(glm::radians(kOuterDeg));  // cone radius on the floor
  const float light_x = params.number("light_x", 1.25f * reach, reach, 1e6f);
  const float intensity = params.number("light_intensity", 10.0f, 0.0f, 1e12f);
  const float floor_albedo = params.number("floor_albedo", 0.8f, 0.0f, 1.0f);
  const float wall_albedo = params.number("wall_albedo", 0.6f, 0.0f, 1.0f);
  MeshBuilder b(scene);
  const uint32_t floor = b.material("floor", glm::vec3(floor_albedo));
  const uint32_t wall = b.material("wall", glm::vec3(wall_albedo));
  b.quad({0.0f, 0.0f, half}, {half, 0.0f, half}, {half, 0.0f, -half}, {0.0f, 0.0f, -half}, floor);
  b.quad({0.0f, 0.0f, -half}, {0.0f, height, -half}, {0.0f, height, half}, {0.0f, 0.0f, half},
         wall);
  scene.light.position = {light_x, light_height, 0.0f};
  scene.light.direction = {0.0f, -1.0f, 0.0f};
  scene.light.intensity = glm::vec3(intensity);
  scene.light.inner_angle_deg = kInnerDeg;
  scene.light.outer_angle_deg = kOuterDeg;
  // From beyond the light, looking at the wall's foot: wall and lit floor side by side.
  scene.camera.eye = {light_x + 1.5f * reach, 1.2f * light_height, 0.0f};
  scene.camera.target = {0.0f, 0.5f * light_height, 0.0f};
  scene.camera.up = {0.0f, 1.0f, 0.0f};
  scene.camera.fov_y_deg = 60.0f;
  read_generator_ao(params, scene, 1.0f);
  return scene;
}

// The inside of a closed diffuse sphere of radius R and albedo ρ with the spot light at its
// centre: an integrating sphere. From any point the form factor to a patch of the sphere is
// its area over 4πR², so whatever the light's pattern, the light reflected once spreads
// evenly: single-bounce irradiance is ρΦ/(4πR²) everywhere, all bounces ρΦ/((1-ρ)4πR²),
// and the outgoing radiance ρ/π times that (up to the tessellation).
Scene make_closed_sphere_scene(GeneratorParams& params) {
  Scene scene;
  scene.name = "closed-sphere";
  const float radius = params.number("radius", 1.0f, 1e-3f, 1e6f);
  const int segments = params.integer("segments", 64, 8, 1024);
  const float albedo = params.number("albedo", 0.5f, 0.0f, 1.0f);
  const float intensity = params.number("light_intensity", 10.0f, 0.0f, 1e12f);
  MeshBuilder b(scene);
  b.sphere(glm::vec3(0.0f), radius, segments, b.material("grey", glm::vec3(albedo)));
  scene.light.position = glm::vec3(0.0f);
  scene.light.direction = {0.0f, -1.0f, 0.0f};
  scene.light.intensity = glm::vec3(intensity);
  scene.light.inner_angle_deg = 30.0f;
  scene.light.outer_angle_deg = 45.0f;
  set_camera(scene, {0.0f, 0.5f * radius, 0.3f * radius}, {0.0f, -radius, -0.2f * radius}, 70.0f);
  read_generator_ao(params, scene, 0.2f * radius);
  return scene;
}

}  // namespace ldm
