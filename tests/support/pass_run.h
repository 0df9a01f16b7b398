#pragma once
// A pass that needs no LDM structure (HBAO, GTAO, the RTAOs), as the pass tests run it:
// declared with `params` and checked as `run` would, then prepared for `scene` at
// width x height. The GPU scene it reads lives as long as the run.
#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "harness/measure/gpu_timer.h"
#include "harness/passes/pass.h"
#include "harness/scene/gpu_scene.h"
#include "harness/scene/scene_loader.h"
#include "harness/util/error.h"
#include "support/test_support.h"

namespace ldm::test {

// The scene attributes the G-buffer passes draw (normals).
inline AttributeSet with_normals() {
  AttributeSet attributes;
  attributes.normals = true;
  return attributes;
}

template <typename Pass>
struct PassRun {
  std::unique_ptr<GpuScene> gpu_scene;
  std::unique_ptr<Pass> pass;

  // `name`: the pass's registered name ("hbao"), as messages name it.
  PassRun(const std::string& name, const Scene& scene, int width, int height,
          std::map<std::string, std::string> params = {},
          const AttributeSet& attributes = with_normals()) {
    gl_context();
    StructureParams p(std::move(params), name + " test");
    p.declare(Pass::parameters());
    pass = std::make_unique<Pass>(p);
    p.check("pass " + name);
    gpu_scene = std::make_unique<GpuScene>(scene, attributes);
    pass->prepare({scene, *gpu_scene, nullptr, nullptr, width, height});
  }

  // One frame; a copy of the pass's (first) image.
  Image render(GpuTimer* timer = nullptr) {
    pass->render(timer);
    return pass->images().front().image;
  }
};

// `name` refuses each parameter value of `refused` with a UserError; with `key`=`value`
// (an integer parameter) it needs no structure, runs on the CPU as `runs_on_cpu` says, and
// the parameter's record column `column` holds that value (pass_parameter_values(), not the
// pass's describe(), which writes none of its parameters' columns).
inline void expect_parameters_checked(
    const std::string& name, const std::vector<std::pair<std::string, std::string>>& refused,
    const std::string& key, int64_t value, const std::string& column, bool runs_on_cpu) {
  for (const auto& [bad_key, bad_value] : refused) {
    EXPECT_THROW(make_pass(name, StructureParams({{bad_key, bad_value}}, "--pass " + name)),
                 UserError)
        << bad_key << "=" << bad_value;
  }
  const auto pass = make_pass(
      name, StructureParams(std::map<std::string, std::string>{{key, std::to_string(value)}}));
  EXPECT_FALSE(pass->requirements().needs_structure);
  EXPECT_EQ(pass->requirements().runs_on_cpu, runs_on_cpu);
  bool found = false;
  for (const auto& [written, written_value] :
       pass_parameter_values(name, {{name + ":" + key, std::to_string(value)}}))
    if (written == column) found = std::get<int64_t>(written_value) == value;
  EXPECT_TRUE(found) << column;
  for (const auto& [described, described_value] : pass->describe(load_scene("cornell")))
    EXPECT_NE(described, column) << "describe() writes a parameter's column";
}

// How rough an AO image is: the sum of squared differences of horizontal neighbours, pairs
// with a background pixel (0) left out (a smoothing pass keeps those edges).
inline double covered_roughness(const Image& image) {
  double sum = 0;
  for (int y = 0; y < image.height; ++y)
    for (int x = 1; x < image.width; ++x) {
      if (image.at(x, y, 0) == 0.0f || image.at(x - 1, y, 0) == 0.0f) continue;
      const double d = image.at(x, y, 0) - image.at(x - 1, y, 0);
      sum += d * d;
    }
  return sum;
}

// A screen-space AO pass's smoothing (HBAO's blur, GTAO's denoise), `smoothing`=2 with
// jitter on cornell: the last of the sub-passes `timed`, its targets counted (two RGBA32F,
// a depth and two R32F targets: 16 + 16 + 4 + 4 + 4 bytes a pixel), and the jittered image
// it smooths is smoother: covered neighbours differ less than without it.
template <typename Pass>
void expect_smoothing_subpass(const std::string& name, const Scene& scene, int size,
                              const std::string& smoothing, const std::vector<std::string>& timed) {
  PassRun<Pass> run(name, scene, size, size, {{smoothing, "2"}, {"jitter", "on"}});
  Pass& pass = *run.pass;
  ASSERT_EQ(pass.subpasses().back().name, timed.back());
  GpuTimer timer(TimerSource::FencedWallClock);
  timer.begin_frame();
  const Image smoothed = run.render(&timer);
  std::vector<std::string> names;
  for (const auto& [subpass, ms] : timer.end_frame()) names.push_back(subpass);
  EXPECT_EQ(names, timed);
  uint64_t total = 0;
  for (const BufferMemory& b : pass.memory()) total += b.allocated;
  EXPECT_EQ(total, uint64_t(size) * size * 44);
  const Image raw = PassRun<Pass>(name, scene, size, size, {{"jitter", "on"}}).render();
  EXPECT_LT(covered_roughness(smoothed), 0.5 * covered_roughness(raw));
}

}  // namespace ldm::test
