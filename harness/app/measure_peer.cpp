#include "harness/app/measure_peer.h"

#include <fstream>
#include <stdexcept>
#include <thread>

#include "harness/app/frame_loop.h"
#include "harness/util/hash.h"

namespace ldm {

std::string cpu_model_name() {
  std::ifstream cpuinfo("/proc/cpuinfo");
  std::string line;
  while (std::getline(cpuinfo, line)) {
    if (line.rfind("model name", 0) != 0) continue;
    const auto colon = line.find(':');
    if (colon == std::string::npos) break;
    const auto start = line.find_first_not_of(" \t", colon + 1);
    if (start != std::string::npos) return "CPU: " + line.substr(start);
  }
  return "CPU: unknown model (" + std::to_string(std::thread::hardware_concurrency()) +
         " hardware threads)";
}

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
  m.scene_gpu_bytes = needs.runs_on_cpu ? 0 : gpu_scene.bytes();
  m.payload = "none";
  pass->prepare({scene, gpu_scene, nullptr, nullptr, request.width, request.height});

  // A CPU pass's time is the CPU's wall time, and its device the CPU: a GPU timer would
  // time nothing (timestamps) or wait on an idle GPU (glFinish).
  m.timer = needs.runs_on_cpu ? TimerSource::CpuWallClock : request.timer;
  if (needs.runs_on_cpu) m.device = cpu_model_name();
  GpuTimer timer(m.timer);
  FrameLoop loop;
  loop.render = [&](GpuTimer& t) { pass->render(&t); };
  loop.add_sums = [](FrameTimes& times) {
    double frame_ms = 0;  // no build: the frame is the pass
    for (const auto& [name, ms] : times) frame_ms += ms;
    times.emplace_back("frame", frame_ms);
  };
  m.frames = run_frame_loop(request, timer, loop);

  m.images = pass->images();
  m.pass_results = pass->results();
  m.memory = pass->memory();
  if (m.images.empty()) throw std::logic_error("pass " + request.pass + " produced no image");
  m.status = BuildStatus::Ok;
  for (const auto& problem : image_problems(m.images)) {
    m.status = BuildStatus::Invalid;
    m.status_detail += (m.status_detail.empty() ? "" : "; ") + problem;
  }
  for (const auto& warning : pass->warnings())
    m.status_detail += (m.status_detail.empty() ? "" : "; ") + warning;
  return m;
}

}  // namespace ldm
