#include <gtest/gtest.h>
#include <cmath>
#include "indirect/indirect_support.h"
#include "harness/scene/spot_light.h"
namespace ldm {
TEST(IndirectDiag, ClosedSphere) {
  for (auto [n, rl, s, dt, a] : {std::tuple{32, 64, 4, 0.1, 4}, {32, 64, 4, 0.1, 0}, {32, 64, 2, 0.1, 2},{32, 64, 8, 0.1, 8},{8, 64, 4, 0.1, 4},{128,64,4,0.1,4}}) {
    Scene scene = load_scene("closed-sphere");
    test::IndirectRun run(scene, "psppsll", n, 64, 64, {{"r_light", std::to_string(rl)}, {"s", std::to_string(s)}, {"depth_threshold", std::to_string(dt)}, {"a", std::to_string(a)}});
    const Image img = run.indirect();
    const Image pos = run.pass->camera_gbuffer().read_positions();
    const float rho = 0.5f, R = 1.0f;
    const double phi = spot_radiant_flux(scene.light).x;
    const double expected = rho * rho * phi / (4 * M_PI * M_PI * R * R);
    double sum = 0, err = 0; int count = 0;
    for (int y = 0; y < img.height; ++y) for (int x = 0; x < img.width; ++x) {
      if (pos.at(x, y, 3) == 0) continue;
      sum += img.at(x, y, 0); err += std::abs(img.at(x, y, 0) - expected); ++count;
    }
    auto c = run.lighting().counts();
    printf("dt %g a %d ", dt, a); printf("N %d Rl %d s %d: mean %g expected %g  rel err %g  prim %lu emit %lu esc %lu depth %lu degen %lu stored %lu\n", n, rl, s, sum / count, expected, err / count / expected,
      c.primary, c.emitted, c.escaped, c.culled_depth, c.degenerate, c.stored);
  }
}
}
