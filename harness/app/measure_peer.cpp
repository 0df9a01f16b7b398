#include "harness/app/measure_peer.h"

#include <stdexcept>

#include "harness/metrics/image_checks.h"
#include "harness/util/error.h"
#include "harness/util/hash.h"

namespace ldm {

Measurement measure_peer(const Scene& scene, const MeasurementRequest& request,
                         std::unique_ptr<Pass> pass) {
  const PassRequirements needs = pass->requirements();
  Measurement m;
  m.scene_name = scene.name;
  m.scene_hash = hex64(scene.content_hash());
  m.triangles = scene.mesh.triangle_count();
  m.structure = "none";
  m.pass = request.pass;
  m.pass_settings = pass->describe(scene);
  for (const auto& s : pass->subpasses()) m.pass_subpasses.push_back(s.name);

  const GpuScene gpu_scene(scene, needs.scene_attributes);
  m.scene_attributes = needs.scene_attributes.describe();
  m.scene_gpu_bytes = gpu_scene.bytes();
  m.payload = "none";
  pass->prepare({scene, gpu_scene, nullptr, nullptr, request.width, request.height});

  m.timer = request.timer;
  GpuTimer timer(request.timer);
  auto keep_running = [&, measured = 0]() mutable {
    if (request.keep_running) return request.keep_running();
    return measured++ < request.frames;
  };
  for (int frame = 0;; ++frame) {
    const bool warmup = frame < request.warmup;
    if (!warmup && !keep_running()) break;
    timer.begin_frame();
    pass->render(&timer);
    FrameTimes times = timer.end_frame();
    if (warmup) continue;
    double frame_ms = 0;
    for (const auto& [name, ms] : times) frame_ms += ms;
    times.emplace_back("frame", frame_ms);
    if (request.on_frame) request.on_frame(times);
    m.frames.push_back(std::move(times));
  }

  m.images = pass->images();
  m.pass_results = pass->results();
  if (m.images.empty()) throw std::logic_error("pass " + request.pass + " produced no image");
  m.status = BuildStatus::Ok;
  for (const auto& image : m.images) {
    try {
      require_finite(image.image, image.name + " image");
    } catch (const UserError& e) {
      m.status = BuildStatus::Invalid;
      m.status_detail += std::string(m.status_detail.empty() ? "" : "; ") +
                         "image not measured: " + e.what();
    }
  }
  for (const auto& warning : pass->warnings())
    m.status_detail += (m.status_detail.empty() ? "" : "; ") + warning;
  return m;
}

}  // namespace ldm
