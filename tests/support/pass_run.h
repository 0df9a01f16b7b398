#pragma once
// A pass that needs no LDM structure (HBAO, GTAO, the RTAOs), as the pass tests run it:
// declared with `params` and checked as `run` would, then prepared for `scene` at
// width x height. The GPU scene it reads lives as long as the run.
#include <map>
#include <memory>
#include <string>

#include "harness/measure/gpu_timer.h"
#include "harness/passes/pass.h"
#include "harness/scene/gpu_scene.h"
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

}  // namespace ldm::test
