#include "harness/app/measurement.h"

#include <algorithm>
#include <stdexcept>

#include "harness/app/frame_loop.h"
#include "harness/app/ldm_setup.h"
#include "harness/app/measure_peer.h"
#include "harness/metrics/image_checks.h"
#include "harness/passes/raster_baseline.h"
#include "harness/records/record.h"
#include "harness/util/error.h"
#include "harness/util/hash.h"
#include "ldm_impls/common/ldm_inspector.h"
#include "ldm_impls/common/sizing_driver.h"

namespace ldm {
namespace {

CensusSummary summarize_census(const FragmentCensus& census) {
  CensusSummary s;
  s.fragments = census.total_fragments;
  s.max_depth_complexity = census.max_depth_complexity;
  s.mean_depth_complexity = census.mean_depth_complexity();
  s.nonempty_pixel_fraction =
      census.total_pixels ? double(census.nonempty_pixels) / double(census.total_pixels) : 0.0;
  return s;
}

// Adds the sums "build" (the structure's sub-passes: all but the baselines and the pass's
// own) and "frame" (all but the baselines) to one frame's times.
void add_frame_sums(FrameTimes& times, const std::vector<std::string>& pass_subpasses) {
  double build_ms = 0, frame_ms = 0;
  for (const auto& [name, ms] : times) {
    // The baselines are timed beside the build but belong to neither the build nor the
    // frame: they are the yardsticks the build is compared with (build_vs_raster*).
    if (RasterBaseline::is_baseline_subpass(name)) continue;
    frame_ms += ms;
    if (std::find(pass_subpasses.begin(), pass_subpasses.end(), name) == pass_subpasses.end())
      build_ms += ms;
  }
  times.emplace_back("build", build_ms);
  times.emplace_back("frame", frame_ms);
}

}  // namespace

std::vector<TimingSummary> Measurement::summaries() const {
  TimingSeries series;
  for (const auto& frame : frames) series.add_frame(frame);
  return series.summarize();
}

std::string frame_samples_csv(const Measurement& m) {
  std::string out = "frame,subpass,ms\n";
  for (size_t frame = 0; frame < m.frames.size(); ++frame)
    for (const auto& [name, ms] : m.frames[frame])
      out += std::to_string(frame) + "," + name + "," + format_csv_value(ms) + "\n";
  return out;
}

uint64_t Measurement::bytes_allocated() const {
  uint64_t total = 0;
  for (const auto& m : memory) total += m.allocated;
  return total;
}

uint64_t Measurement::bytes_used() const {
  uint64_t total = 0;
  for (const auto& m : memory) total += m.used;
  return total;
}

std::vector<std::string> image_problems(const std::vector<PassImage>& images) {
  std::vector<std::string> problems;
  for (const auto& image : images) {
    try {
      require_finite(image.image, image.name + " image");
    } catch (const UserError& e) {
      problems.push_back(std::string("image not measured: ") + e.what());
    }
  }
  return problems;
}

Measurement measure(const Scene& scene, const MeasurementRequest& request) {
  auto pass = make_pass(request.pass, StructureParams(request.pass_params, "--pass " + request.pass));
  const PassRequirements needs = pass->requirements();
  if (!needs.needs_structure) return measure_peer(scene, request, std::move(pass));

  Measurement m;
  m.scene_name = scene.name;
  m.scene_hash = hex64(scene.content_hash());
  m.triangles = scene.mesh.triangle_count();
  m.structure = request.structure;
  m.pass = request.pass;
  m.pass_settings = pass->describe(scene);
  for (const auto& s : pass->subpasses()) m.pass_subpasses.push_back(s.name);

  // Only what the pass reads is uploaded, and the structure stores only its payload.
  const LdmSetup setup(scene, needs.scene_attributes, request.views, request.resolution,
                       needs.payload, request.sizing);
  const FragmentCensus& census = setup.census;
  const BuildInputs& in = *setup.inputs;
  m.scene_attributes = needs.scene_attributes.describe();
  m.scene_gpu_bytes = setup.gpu_scene->bytes();
  m.payload = in.payload.describe();
  m.census = summarize_census(census);

  auto structure = setup.prepare(request.structure, request.structure_params);
  const RasterBaseline baseline(*setup.raster, setup.views);
  pass->prepare({setup.scene, *setup.gpu_scene, &in, structure.get(), request.width,
                 request.height});
  // Verification reads the census (never sizing): a list longer than its deepest pixel is
  // corrupt.
  const LdmInspector inspector(*structure, in, std::max(1u, census.max_depth_complexity));
  SizingDriver sizer(*structure, in);
  uint64_t rebuilds_in_warmup = 0;

  m.timer = request.timer;
  GpuTimer timer(request.timer);
  BuildHealth health(census);
  if (census.max_depth_complexity > kMaxListWalk)
    health.report_problem("a pixel holds " + std::to_string(census.max_depth_complexity) +
                          " fragments, more than list walks follow (" +
                          std::to_string(kMaxListWalk) + ")");
  // One frame: the yardstick, the build, the pass. Work that belongs to the build (e.g. a
  // per-frame census, or a rebuild after an overflow under a sizing policy) goes between
  // begin_frame() and pass->render(), timed under its own sub-pass name, so that it counts
  // as build time; the pass then reads the finished structure.
  FrameLoop loop;
  loop.render = [&](GpuTimer& t) {
    baseline.render(&t);
    sizer.build(&t);  // the structure's build() under its sizing policy
    pass->render(&t);
  };
  loop.after_frame = [&](bool warmup) {
    // Untimed: what the build stored, read back through the query API.
    m.last_build = structure->stats();
    health.observe(m.last_build, inspector.check());
    if (warmup) rebuilds_in_warmup = sizer.rebuilds();
  };
  loop.add_sums = [&](FrameTimes& times) { add_frame_sums(times, m.pass_subpasses); };
  m.frames = run_frame_loop(request, timer, loop);

  // A touch baseline that shaded other fragments than the census would make
  // build_vs_raster_touch a ratio to something else.
  m.raster_touch_fragments = baseline.touched_fragments();
  if (m.raster_touch_fragments != census.total_fragments)
    health.report_problem("the raster_touch baseline shaded " +
                          std::to_string(m.raster_touch_fragments) +
                          " fragments where the census counted " +
                          std::to_string(census.total_fragments));
  m.images = pass->images();
  m.pass_results = pass->results();
  if (m.images.empty()) throw std::logic_error("pass " + request.pass + " produced no image");
  for (const auto& problem : image_problems(m.images)) health.report_problem(problem);
  m.status = health.status();
  m.status_detail = health.detail();
  for (const auto& warning : pass->warnings())  // measured, but known to be off: say so
    m.status_detail += (m.status_detail.empty() ? "" : "; ") + warning;
  m.overflow = health.overflow();
  m.checksum_changes = health.checksum_changes();
  m.lists_checksum = health.first_checksum();
  m.sizing = structure->sizing();
  for (const auto& entry : sizer.describe()) m.sizing.push_back(entry);
  m.sizing_rebuilds = sizer.rebuilds();
  m.sizing_rebuilds_measured = sizer.rebuilds() - rebuilds_in_warmup;
  m.sizing_reallocations = sizer.reallocations();
  m.memory = structure->memory();
  for (const auto& buffer : sizer.memory()) m.memory.push_back(buffer);
  return m;
}

}  // namespace ldm
