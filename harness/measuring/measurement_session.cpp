#include "harness/measuring/measurement_session.h"

#include <cstdio>
#include <cstring>

#include <algorithm>
#include <cmath>
#include <chrono>
#include <optional>
#include <stdexcept>

#include "harness/gl/gl_objects.h"
#include "harness/measuring/ldm_setup.h"
#include "harness/settings/record_schema.h"
#include "harness/measure/work_counters.h"
#include "harness/records/harness_columns.h"
#include "harness/metrics/image_checks.h"
#include "harness/passes/raster_baseline.h"
#include "harness/util/error.h"
#include "harness/util/hash.h"
#include "ldm_impls/common/build_verifier.h"
#include "ldm_impls/common/ldm_inspector.h"
#include "ldm_impls/common/sizing_driver.h"
#include "ldm_impls/common/storage_fit.h"

namespace ldm {
namespace {

using namespace columns;

// The fragment census in the few numbers a record keeps.
void set_census_columns(Record& r, const FragmentCensus& census) {
  r.set(kFragments, census.total_fragments);
  r.set(kMaxDepthComplexity, census.max_depth_complexity);
  r.set(kMeanDepthComplexity, census.mean_depth_complexity());
  r.set(kNonemptyPixelFraction,
        census.total_pixels ? double(census.nonempty_pixels) / double(census.total_pixels) : 0.0);
}

// The record's memory columns: every buffer's mem_<name>_allocated and _used, then the
// structure's (or a peer pass's) totals; the pass's own buffers beside a structure's are
// listed but not in the totals.
void set_memory_columns(Record& r, const std::vector<BufferMemory>& counted,
                        const std::vector<BufferMemory>& listed_only) {
  for (const auto* buffers : {&counted, &listed_only})
    for (const auto& b : *buffers) {
      r.set("mem_" + b.name + "_allocated", b.allocated);
      r.set("mem_" + b.name + "_used", b.used);
    }
  uint64_t allocated = 0, used = 0;
  for (const auto& b : counted) {
    allocated += b.allocated;
    used += b.used;
  }
  r.set(kBytesAllocated, allocated);
  r.set(kBytesUsed, used);
}

// Adds the sums "build" (the structure's sub-passes: all but the baselines and the pass's
// own), "pass" (the pass's own) and "frame" (all but the baselines) to one frame's times.
// Summed per frame, so that each sum has its own interval (a sum of medians has none).
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
  times.emplace_back("pass", frame_ms - build_ms);
  times.emplace_back("frame", frame_ms);
}

std::unique_ptr<Pass> make_request_pass(const MeasurementRequest& request) {
  const Configuration& config = request.configuration;
  return make_pass(config.pass, StructureParams(config.pass_params, "--pass " + config.pass));
}

}  // namespace

// Everything one configuration's frames need. The LDM members are empty for a peer pass,
// which has only `peer_scene` and `peer_gpu_scene`.
struct MeasurementSession::State {
  MeasurementRequest request;
  std::unique_ptr<Pass> pass;
  Measurement m;  // the columns fixed before the first frame, and the kept frames
  std::string structure_name;  // the configuration's structure; "none" for a peer pass
  int frames_run = 0;
  GpuTimer timer;

  // LDM passes.
  std::unique_ptr<LdmSetup> setup;
  std::unique_ptr<LdmStructure> structure;
  std::unique_ptr<RasterBaseline> baseline;
  std::unique_ptr<LdmInspector> inspector;
  std::unique_ptr<SizingDriver> sizer;
  std::optional<BuildHealth> health;
  std::unique_ptr<BuildVerifier> verifier;
  uint64_t rebuilds_in_warmup = 0;
  uint64_t sizing_changes_seen = 0;  // rebuilds + reallocations at the last verification
  BuildStats last_build;  // stats() of the last build
  // The wall time the builds' checks took (warm-up, measured).
  double verify_warmup_ms = 0, verify_measured_ms = 0;
  // The counting replay's columns (count_work(): work_replay_ms, the work_* counters).
  Record work_columns = measurement_record();
  // Where the counting replay disagreed with the measured frames (count_work()).
  std::vector<std::string> work_problems;
  // measured_result() taken just before the counting replay wrote into the measured
  // instances' storage (what the replay borrows); dropped when a later frame runs.
  std::optional<Measurement> before_replay;

  // Peer passes: the scene as given (no LDM views, so no centred frame is imposed).
  std::unique_ptr<Scene> peer_scene;
  std::unique_ptr<GpuScene> peer_gpu_scene;

  State(const MeasurementRequest& r, std::unique_ptr<Pass> p, TimerSource source)
      : request(r), pass(std::move(p)), timer(source) {}

  Scene& scene() { return setup ? setup->scene : *peer_scene; }
  // What tags the storage the counting replay borrows (GlBufferLoanScope): the structure's
  // (and its sizing's), and the pass's.
  const void* structure_storage() const { return &structure; }
  const void* pass_storage() const { return &pass; }
  void prepare_pass() {
    const GlBufferOwnerScope owner(pass_storage());
    const Configuration& config = request.configuration;
    if (setup)
      pass->prepare({setup->scene, *setup->gpu_scene, setup->inputs.get(), structure.get(), config.width,
                     config.height, &config.values});
    else
      pass->prepare({*peer_scene, *peer_gpu_scene, nullptr, nullptr, config.width, config.height, &config.values});
  }
};

MeasurementSession::MeasurementSession(const Scene& scene, const MeasurementRequest& request)
    : state_() {
  if (request.configuration.width <= 0 || request.configuration.height <= 0)
    throw std::logic_error("the configuration " + request.configuration.id() + " has no image size");
  auto pass = make_request_pass(request);
  const PassRequirements needs = pass->requirements();
  // A CPU pass's time is the CPU's wall time, and its device the CPU: a GPU timer would
  // time nothing (timestamps) or wait on an idle GPU (glFinish).
  const TimerSource timer_source = needs.runs_on_cpu ? TimerSource::CpuWallClock : request.timer;
  state_ = std::make_unique<State>(request, std::move(pass), timer_source);
  State& s = *state_;
  Measurement& m = s.m;
  Record& r = m.columns = measurement_record();
  const Configuration& config = request.configuration;
  r.set(kSceneName, scene.name);
  r.set(kSceneHash, hex64(scene.content_hash()));
  r.set(kTriangles, scene.mesh.triangle_count());
  for (const auto& [key, value] : s.pass->describe(scene)) r.put(key, value);
  // Every parameter's own column, by one loop over the pass's declarations: what the
  // configuration gives, else the declared default.
  for (const auto& [column, value] : pass_parameter_values(config.pass, config.values)) r.put(column, value);
  for (const auto& sub : s.pass->subpasses()) m.pass_subpasses.push_back(sub.name);
  r.set(kSceneAttributes,
        needs.scene_attributes.describe(scene.derived_normal_triangles, scene.mesh.triangle_count()));
  // Last of the columns known before the first frame, whichever kind of pass.
  const auto set_timer_columns = [&] {
    r.set(kTimer, timer_source_name(timer_source));
    if (needs.runs_on_cpu) r.set(kDevice, cpu_model_name());  // not GL_RENDERER: the CPU
  };

  if (!needs.needs_structure) {
    // A screen-space or ray-traced peer such as HBAO: the scene uploaded with the attributes
    // the pass asks for, then frames of the pass alone. No census, views, baselines or
    // build: the record's structure is "none" and its "frame" time is the pass's whole cost.
    s.structure_name = kNoStructure;
    s.peer_scene = std::make_unique<Scene>(scene);
    s.peer_gpu_scene = std::make_unique<GpuScene>(*s.peer_scene, needs.scene_attributes);
    r.set(kSceneGpuBytes, needs.runs_on_cpu ? 0 : s.peer_gpu_scene->bytes());
    r.set(kPayload, "none");
    set_timer_columns();
    s.prepare_pass();
    return;
  }

  s.structure_name = config.structure;
  // Only what the pass reads is uploaded, and the structure stores only its payload.
  s.setup = std::make_unique<LdmSetup>(scene, needs.scene_attributes, config.views, config.resolution,
                                       needs.payload, config.sizing);
  const FragmentCensus& census = s.setup->census;
  const BuildInputs& in = *s.setup->inputs;
  r.set(kSceneGpuBytes, s.setup->gpu_scene->bytes());
  r.set(kPayload, in.payload.describe());
  set_census_columns(r, census);
  set_timer_columns();
  m.depth_profile = depth_profile(census);

  try {
    const GlBufferOwnerScope owner(s.structure_storage());
    s.structure = s.setup->prepare(config.structure, config.params);
  } catch (const StorageBlockExceeded& e) {  // say what would fit, from the census
    throw explained_refusal(e, census, config.views, config.resolution);
  }
  s.baseline = std::make_unique<RasterBaseline>(*s.setup->raster, s.setup->views);
  s.prepare_pass();
  // Verification reads the census (never sizing): a list longer than its deepest pixel is
  // corrupt.
  s.inspector = std::make_unique<LdmInspector>(*s.structure, in,
                                               std::max(1u, census.max_depth_complexity));
  {
    const GlBufferOwnerScope owner(s.structure_storage());
    s.sizer = std::make_unique<SizingDriver>(*s.structure, in);
  }
  s.health.emplace(census);
  s.verifier = std::make_unique<BuildVerifier>(*s.structure, *s.inspector, *s.health,
                                               request.verify, request.verify_stride);
  if (census.max_depth_complexity > kMaxListWalk)
    s.health->report_problem("a pixel holds " + std::to_string(census.max_depth_complexity) +
                             " fragments, more than list walks follow (" +
                             std::to_string(kMaxListWalk) + ")");
}

MeasurementSession::~MeasurementSession() = default;

// One frame: the yardstick, the build, the pass. Work that belongs to the build (e.g. a
// per-frame census, or a rebuild after an overflow under a sizing policy) goes between
// begin_frame() and pass->render(), timed under its own sub-pass name, so that it counts
// as build time; the pass then reads the finished structure.
FrameTimes MeasurementSession::run_frame() {
  State& s = *state_;
  s.before_replay.reset();  // this frame's readings are the measured instances' again
  const bool warmup = in_warmup();
  // The yardsticks on the first warm-up frame (their programs' first use) and on every
  // kBaselineFrameStride-th measured frame from the first: they are compared with the
  // build's median, for which a subset of frames suffices, and cost a build's worth each.
  const int measured_index = s.frames_run - s.request.warmup;
  const bool yardsticks = warmup ? s.frames_run == 0 : measured_index % kBaselineFrameStride == 0;
  ++s.frames_run;
  s.timer.begin_frame();
  if (s.setup) {
    if (yardsticks) s.baseline->render(&s.timer);
    try {
      const GlBufferOwnerScope owner(s.structure_storage());  // a resize's new storage
      s.sizer->build(&s.timer);  // the structure's build() under its sizing policy
    } catch (const StorageBlockExceeded& e) {  // grown past the device: say what would fit
      throw explained_refusal(e, s.setup->census, s.request.configuration.views,
                              s.request.configuration.resolution);
    }
  }
  {
    const GlBufferOwnerScope owner(s.pass_storage());  // storage the pass grows itself
    s.pass->render(&s.timer);
  }
  FrameTimes times = s.timer.end_frame();
  if (s.setup) {
    // Untimed: what the build stored, read back through the query API (in full, or a
    // sample of it: build_verifier.h); its wall time is the harness's own cost.
    const auto verify_start = std::chrono::steady_clock::now();
    const uint64_t sizing_changes = s.sizer->rebuilds() + s.sizer->reallocations();
    s.verifier->verify(sizing_changes != s.sizing_changes_seen);
    s.sizing_changes_seen = sizing_changes;
    s.last_build = s.verifier->last_stats();
    const double verify_ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - verify_start).count();
    (warmup ? s.verify_warmup_ms : s.verify_measured_ms) += verify_ms;
    if (warmup) {  // judged, but not measured
      s.rebuilds_in_warmup = s.sizer->rebuilds();
      return times;
    }
    add_frame_sums(times, s.m.pass_subpasses);
  } else {
    if (warmup) return times;
    double frame_ms = 0;
    for (const auto& [name, ms] : times) frame_ms += ms;
    times.emplace_back("pass", frame_ms);
    times.emplace_back("frame", frame_ms);
  }
  s.m.frames.push_back(times);
  return times;
}

namespace {

// How many values of two images differ by more than `tolerance` relative to the larger of
// the two (0: bit for bit; a shape mismatch: all of them).
size_t differing_values(const Image& a, const Image& b, double tolerance) {
  if (!a.same_shape(b)) return std::max(a.pixels.size(), b.pixels.size());
  if (std::isinf(tolerance)) return 0;  // the pass says its images depend on arrival order
  size_t differing = 0;
  for (size_t i = 0; i < a.pixels.size(); ++i) {
    if (std::memcmp(&a.pixels[i], &b.pixels[i], sizeof(float)) == 0) continue;
    const double x = a.pixels[i], y = b.pixels[i];
    if (tolerance > 0 && std::abs(x - y) <= tolerance * std::max(std::abs(x), std::abs(y))) continue;
    ++differing;
  }
  return differing;
}

}  // namespace

void MeasurementSession::count_work() {
  State& s = *state_;
  if (s.pass->requirements().runs_on_cpu) return;  // no shader to count (the CPU ray tracer)
  const Configuration& config = s.request.configuration;
  // The replay borrows the measured buffers and overwrites them: read the measured frames'
  // results, memory in use and losses first, so that the record keeps theirs.
  s.before_replay = measured_result();
  const auto start = std::chrono::steady_clock::now();
  WorkCounterBuffer counts(configuration_work_counters(s.structure_name, config.pass));
  GpuTimer timer(TimerSource::CpuWallClock);  // only to tell the counters the sub-passes
  timer.set_observer(&counts);
  std::unique_ptr<LdmStructure> structure;
  std::unique_ptr<SizingDriver> sizer;
  std::unique_ptr<Pass> pass;
  // The replay, its construction totals counted by blending where it may
  // (ldm_impls/common/blended_work_counts.h); what it reports where a blended sum may have
  // passed the float range in which it is exact.
  const auto replay = [&](bool blend_totals) {
    WorkCountingScope counting(counts.defines(), blend_totals, &counts);
    pass.reset();  // a pass and a sizer refer to the structure: gone before it
    sizer.reset();
    structure.reset();
    pass = make_request_pass(s.request);
    // The replay's structure, sizing and pass take the measured instances' buffers where
    // they ask for the same ones (already allocated at their settled sizes and touched:
    // gl_objects.h) instead of allocating new storage. The measured instances' contents are
    // overwritten: the check below compares with what the measured frames recorded (the
    // lists' first checksum) and with their images (textures, never lent).
    if (s.setup) {
      {
        const GlBufferLoanScope loan(s.structure_storage());
        structure = s.setup->prepare(config.structure, config.params);
        sizer = std::make_unique<SizingDriver>(*structure, *s.setup->inputs);
      }
      const GlBufferLoanScope loan(s.pass_storage());
      pass->prepare({s.setup->scene, *s.setup->gpu_scene, s.setup->inputs.get(), structure.get(), config.width,
                     config.height, &config.values});
      pass->continue_sizing_from(*s.pass);
    } else {
      const GlBufferLoanScope loan(s.pass_storage());
      pass->prepare({*s.peer_scene, *s.peer_gpu_scene, nullptr, nullptr, config.width, config.height,
                     &config.values});
    }
    auto frame = [&] {
      timer.begin_frame();
      if (sizer) {
        const GlBufferLoanScope loan(s.structure_storage());
        sizer->build(&timer);
      }
      {
        const GlBufferLoanScope loan(s.pass_storage());
        pass->render(&timer);
      }
      timer.end_frame();
    };
    // One counted frame, its structure sized as the measured frames' next would be. Where
    // a sizing policy still grew inside it (the indirect pass's photon buffer under
    // previous_frame, which the pass sizes itself), its rebuild counted the work twice:
    // that frame settled the sizes, and the next one is counted.
    if (sizer) {
      const GlBufferLoanScope loan(s.structure_storage());
      sizer->continue_from(*s.sizer);
    }
    counts.clear();
    frame();
    if (counts.began("rebuild") || counts.began("photon_rebuild")) {
      counts.clear();
      frame();
    }
    return counting.inexact_blends();
  };
  const std::vector<std::string> inexact = replay(true);
  if (!inexact.empty()) {
    // Rare (a pixel's total past 2^24 needs thousands of fragments over the views): counted
    // again, every site an atomic, so that the record's counts are exact.
    std::fprintf(stderr, "the counting replay of %s: %s; counted again with atomics\n",
                 s.setup ? s.structure_name.c_str() : "the pass", inexact.front().c_str());
    replay(false);
  }
  const std::vector<std::pair<std::string, RecordValue>> work = counts.read(&s.work_problems);

  // Counting must change nothing the measured frames computed: the same sorted lists (the
  // raw buffers may differ where fragments race) and bit for bit the same images.
  if (structure) {
    const LdmInspector inspector(*structure, *s.setup->inputs,
                                 std::max(1u, s.setup->census.max_depth_complexity));
    const LdmIntegrity replayed = inspector.check();
    if (replayed.checksum != s.health->first_checksum())
      s.work_problems.push_back("the counting replay's sorted lists differ from the measured builds' "
                                "(checksum " + hex64(replayed.checksum) + " against " +
                                hex64(s.health->first_checksum()) + ")");
  }
  const std::vector<PassImage> measured = s.pass->images(), replayed = pass->images();
  for (size_t i = 0; i < measured.size() && i < replayed.size(); ++i)
    if (const size_t differing = differing_values(measured[i].image, replayed[i].image,
                                                  s.pass->image_order_tolerance()))
      s.work_problems.push_back("the counting replay's " + measured[i].name + " image differs from the "
                                "measured frames' in " + std::to_string(differing) + " values" +
                                (s.pass->image_order_tolerance() > 0 ? " beyond the pass's order tolerance" : ""));
  if (measured.size() != replayed.size())
    s.work_problems.push_back("the counting replay drew another number of images");
  s.work_columns.set(kWorkReplayMs,
                    std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
  for (const auto& [column, value] : work) s.work_columns.put(column, value);
}

int MeasurementSession::frames_run() const { return state_->frames_run; }
bool MeasurementSession::in_warmup() const { return state_->frames_run < state_->request.warmup; }

void MeasurementSession::add_warmup_frame() {
  State& s = *state_;
  s.request.warmup = std::max(s.request.warmup, s.frames_run) + 1;
}

Measurement MeasurementSession::result() const {
  const State& s = *state_;
  Measurement m = s.before_replay ? *s.before_replay : measured_result();
  m.columns.put_all(s.work_columns);
  // Where counting changed what the measured frames computed, the record is invalid.
  if (!s.work_problems.empty()) m.columns.set(kStatus, build_status_name(BuildStatus::Invalid));
  for (const auto& problem : s.work_problems) append_note(m.columns, kStatusDetail, problem);
  return m;
}

Measurement MeasurementSession::measured_result() const {
  const State& s = *state_;
  Measurement m = s.m;
  Record& r = m.columns;
  m.images = s.pass->images();
  m.coverage = s.pass->coverage();
  if (m.images.empty()) throw std::logic_error("pass " + s.request.configuration.pass + " produced no image");
  for (const auto& [key, value] : s.pass->results()) r.put(key, value);
  const std::vector<std::string> problems = image_problems(m.images);
  BuildStatus status = BuildStatus::Ok;
  std::string detail;
  const auto note = [&detail](const std::string& text) { detail += (detail.empty() ? "" : "; ") + text; };
  if (!s.setup) {
    // The image's own problems and the pass's (e.g. a GPU ray tracer the device's loop limit
    // may have cut short) make a peer's record invalid, as they do an LDM pass's.
    std::vector<std::string> all_problems = problems;
    for (const auto& problem : s.pass->problems()) all_problems.push_back(problem);
    status = all_problems.empty() ? BuildStatus::Ok : BuildStatus::Invalid;
    for (const auto& problem : all_problems) note(problem);
    m.memory = s.pass->memory();
    set_memory_columns(r, m.memory, {});
  } else {
    BuildHealth health = *s.health;  // a snapshot: later frames are judged afresh
    // A touch baseline that shaded other fragments than the census would make
    // build_vs_raster_touch a ratio to something else.
    const uint64_t touched = s.baseline->touched_fragments();
    if (touched != s.setup->census.total_fragments)
      health.report_problem("the raster_touch baseline shaded " + std::to_string(touched) +
                            " fragments where the census counted " +
                            std::to_string(s.setup->census.total_fragments));
    for (const auto& problem : problems) health.report_problem(problem);
    for (const auto& problem : s.pass->problems()) health.report_problem(problem);
    status = health.status();
    detail = health.detail();
    r.set(kFragmentsStored, s.last_build.fragments_stored);
    r.set(kFragmentsLost, s.last_build.fragments_lost);
    r.set(kOverflow, health.overflow());
    r.set(kChecksumChanges, health.checksum_changes());
    r.set(kTiedDepths, health.tied_depths());
    r.set(kListsChecksum, hex64(health.first_checksum()));
    // Ties in a structure that quantises depths may be distinct depths collided on one key:
    // their order is lost, which the record says rather than passing as exact (issue 35).
    if (const double quantum = s.structure->depth_quantum(s.setup->views.views.front());
        health.tied_depths() > 0 && quantum > 0.0) {
      char text[320];
      std::snprintf(text, sizeof text,
                    "%llu fragments stored at their predecessor's quantised depth (depth_quantum %.3g): "
                    "distinct depths within one key step collided, their order lost, or coincident "
                    "surfaces; the keys cannot tell which (tied_depths)",
                    static_cast<unsigned long long>(health.tied_depths()), quantum);
      note(text);
    }
    // How the builds were checked, and the wall time the checks took.
    const VerifyCounts checks = s.verifier->counts();
    r.set(kVerifyMode, verify_mode_name(s.verifier->mode()));
    r.set(kVerifyStride, s.verifier->stride());
    r.set(kVerifyFullChecks, checks.full);
    r.set(kVerifySampledChecks, checks.sampled);
    r.set(kVerifySampledPixels, checks.sampled_pixels);
    r.set(kVerifyMs, s.verify_measured_ms);
    r.set(kVerifyWarmupMs, s.verify_warmup_ms);
    for (const auto& [name, value] : s.last_build.counters) r.set("counter_" + name, value);
    // The structure's sizing() and the policy's (SizingDriver::describe()).
    for (const auto& [key, value] : s.structure->sizing()) r.set("sizing_" + key, value);
    for (const auto& [key, value] : s.sizer->describe()) r.set("sizing_" + key, value);
    // Rebuilds after an overflow (all builds; in measured frames) and reallocations.
    r.set(kSizingRebuilds, s.sizer->rebuilds());
    r.set(kSizingRebuildsMeasured, s.sizer->rebuilds() - s.rebuilds_in_warmup);
    r.set(kSizingReallocations, s.sizer->reallocations());
    // Fragments the last raster_touch pass shaded (harness/passes/raster_baseline.h): the
    // census total when the touch baseline really touched every fragment.
    r.set(kRasterTouchFragments, touched);
    m.memory = s.structure->memory();
    for (const auto& buffer : s.sizer->memory()) m.memory.push_back(buffer);
    set_memory_columns(r, m.memory, s.pass->memory());  // the pass's own: not in bytes_*
    // The pass's own counted loss (e.g. photons beyond the photon buffer) is lossy, as a
    // structure's is; it never hides an invalid verdict.
    const std::string pass_loss = s.pass->loss();
    if (!pass_loss.empty()) {
      if (status == BuildStatus::Ok) status = BuildStatus::Lossy;
      note(pass_loss);
    }
  }
  for (const auto& warning : s.pass->warnings()) note(warning);  // measured, but known to be off: say so
  // What loading the scene replaced by a default (an OBJ's missing .mtl: grey albedo, on
  // which the indirect light depends): in the record, not only on stderr.
  for (const auto& warning : scene().warnings) note(warning);
  r.set(kStatus, build_status_name(status));
  r.set(kStatusDetail, detail);
  return m;
}

const Scene& MeasurementSession::scene() const {
  return state_->setup ? state_->setup->scene : *state_->peer_scene;
}

void MeasurementSession::set_camera(const Camera& camera) {
  State& s = *state_;
  s.scene().camera = camera;
  s.pass = make_request_pass(s.request);
  s.prepare_pass();
}

const Pass& MeasurementSession::pass() const { return *state_->pass; }
const LdmSetup* MeasurementSession::setup() const { return state_->setup.get(); }
const LdmStructure* MeasurementSession::structure() const { return state_->structure.get(); }

}  // namespace ldm
