// The Cornell box with its short and tall blocks, from the Cornell University measurements
// (https://www.graphics.cornell.edu/online/box/data.html), in units of 100 mm. The walls are
// the measured, slightly non-square quadrilaterals. The ceiling light's emitter quad is left
// out (it is coplanar with the ceiling); lighting comes from the scene's spot light.
#include "harness/scene/generators.h"
#include "harness/scene/mesh_builder.h"

namespace ldm {

Scene make_cornell_scene(GeneratorParams& params) {
  const float scale = params.number("scale", 0.01f, 1e-4f, 1e4f);  // scene units per mm
  const bool blocks = params.boolean("blocks", true);
  Scene scene;
  scene.name = "cornell";
  MeshBuilder b(scene);
  const uint32_t white = b.material("white", {0.73f, 0.73f, 0.73f});
  const uint32_t red = b.material("red", {0.63f, 0.065f, 0.05f});
  const uint32_t green = b.material("green", {0.14f, 0.45f, 0.091f});
  auto p = [scale](float x, float y, float z) { return glm::vec3(x, y, z) * scale; };

  // Quads listed counter-clockwise as seen from inside the box.
  b.quad(p(552.8f, 0, 0), p(0, 0, 0), p(0, 0, 559.2f), p(549.6f, 0, 559.2f), white);  // floor
  b.quad(p(556.0f, 548.8f, 0), p(556.0f, 548.8f, 559.2f), p(0, 548.8f, 559.2f),
         p(0, 548.8f, 0), white);  // ceiling
  b.quad(p(549.6f, 0, 559.2f), p(0, 0, 559.2f), p(0, 548.8f, 559.2f),
         p(556.0f, 548.8f, 559.2f), white);  // back wall
  b.quad(p(0, 0, 559.2f), p(0, 0, 0), p(0, 548.8f, 0), p(0, 548.8f, 559.2f),
         green);  // right wall (x = 0)
  b.quad(p(552.8f, 0, 0), p(549.6f, 0, 559.2f), p(556.0f, 548.8f, 559.2f),
         p(556.0f, 548.8f, 0), red);  // left wall

  if (blocks) {
    // Short block: top and four sides, counter-clockwise from outside.
    b.quad(p(130, 165, 65), p(82, 165, 225), p(240, 165, 272), p(290, 165, 114), white);
    b.quad(p(290, 0, 114), p(290, 165, 114), p(240, 165, 272), p(240, 0, 272), white);
    b.quad(p(130, 0, 65), p(130, 165, 65), p(290, 165, 114), p(290, 0, 114), white);
    b.quad(p(82, 0, 225), p(82, 165, 225), p(130, 165, 65), p(130, 0, 65), white);
    b.quad(p(240, 0, 272), p(240, 165, 272), p(82, 165, 225), p(82, 0, 225), white);
    // Tall block.
    b.quad(p(423, 330, 247), p(265, 330, 296), p(314, 330, 456), p(472, 330, 406), white);
    b.quad(p(423, 0, 247), p(423, 330, 247), p(472, 330, 406), p(472, 0, 406), white);
    b.quad(p(472, 0, 406), p(472, 330, 406), p(314, 330, 456), p(314, 0, 456), white);
    b.quad(p(314, 0, 456), p(314, 330, 456), p(265, 330, 296), p(265, 0, 296), white);
    b.quad(p(265, 0, 296), p(265, 330, 296), p(423, 330, 247), p(423, 0, 247), white);
  }

  // The measured camera: 35 mm focal length, 25 mm film, 800 mm in front of the opening.
  scene.camera.eye = p(278, 273, -800);
  scene.camera.target = p(278, 273, 0);
  scene.camera.up = {0, 1, 0};
  scene.camera.fov_y_deg = 39.3077f;  // 2 atan(12.5 / 35)
  // A spot light just under the ceiling's light opening, pointing down.
  scene.light.position = p(278, 540, 279.5f);
  scene.light.direction = {0, -1, 0};
  scene.light.intensity = glm::vec3(params.number("light_intensity", 8.0f, 0.0f, 1e6f));
  scene.light.inner_angle_deg = 50.0f;
  scene.light.outer_angle_deg = 70.0f;
  scene.ao.attenuated = true;
  scene.ao.d_max = params.number("d_max", 150.0f * scale, 1e-6f, 1e6f);
  return scene;
}

}  // namespace ldm
