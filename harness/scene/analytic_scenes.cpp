// Scenes whose ambient occlusion has a closed form (tests/ao derive and check them). Planes
// are large compared with d_max so that, with attenuated visibility, they act as infinite.
#include "harness/scene/generators.h"
#include "harness/scene/mesh_builder.h"

namespace ldm {
namespace {

void floor_square(MeshBuilder& b, float half, float y, uint32_t material) {
  b.quad({-half, y, half}, {half, y, half}, {half, y, -half}, {-half, y, -half}, material);
}

void read_ao(GeneratorParams& params, Scene& scene, float default_d_max) {
  scene.ao.attenuated = params.boolean("attenuated", true);
  scene.ao.d_max = params.number("d_max", default_d_max, 1e-6f, 1e6f);
  scene.ao.normal_offset_pixels = params.number("normal_offset", 0.0f, 0.0f, 100.0f);
}

}  // namespace

Scene make_plane_scene(GeneratorParams& params) {
  Scene scene;
  scene.name = "plane";
  const float half = params.number("half_size", 4.0f, 1e-3f, 1e6f);
  MeshBuilder b(scene);
  floor_square(b, half, 0.0f, b.material("grey", glm::vec3(0.5f)));
  scene.camera.eye = {0.0f, 1.0f, 0.0f};
  scene.camera.target = {0.0f, 0.0f, 0.0f};
  scene.camera.up = {0.0f, 0.0f, -1.0f};
  scene.camera.fov_y_deg = 60.0f;
  scene.light.position = {0.0f, 3.0f, 0.0f};
  read_ao(params, scene, 1.0f);
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
  scene.camera.eye = {0.0f, 0.9f * h, 0.0f};
  scene.camera.target = {0.0f, 0.0f, 0.0f};
  scene.camera.up = {0.0f, 0.0f, -1.0f};
  scene.camera.fov_y_deg = 60.0f;
  scene.light.position = {0.0f, 0.8f * h, 0.0f};
  read_ao(params, scene, 2.0f * h);
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
  scene.camera.eye = {0.6f, 1.2f, 0.0f};
  scene.camera.target = {0.6f, 0.0f, 0.0f};
  scene.camera.up = {0.0f, 0.0f, -1.0f};
  scene.camera.fov_y_deg = 50.0f;
  scene.light.position = {1.0f, 3.0f, 0.0f};
  read_ao(params, scene, 1.0f);
  return scene;
}

}  // namespace ldm
