#pragma once
// The interface every measured pass implements, as ldm_impls/ldm_structure.h is for the
// structures: ambient occlusion is the first; indirect light and the screen-space or
// ray-traced peers plug in the same way.
//
// A pass declares what it needs (scene attributes to upload, per-fragment payload for the
// structures to store, whether it reads an LDM structure at all), reads its parameters in
// its constructor through StructureParams' checked getters (so unknown keys and
// out-of-range values are errors before any GPU work), names the sub-passes it times, gives
// its output images, and renders (or fetches from the disk cache) the converged reference
// its first image estimates.
//
// Adding a pass touches its own files (harness/passes/<name>*, shaders/passes/, its
// reference renderer under harness/reference/) and one line in
// harness/passes/pass_registry.cpp.
#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "harness/axes/axis.h"
#include "harness/image/image.h"
#include "harness/measure/gpu_timer.h"
#include "harness/measure/work_counters.h"
#include "harness/records/columns.h"
#include "harness/records/record.h"
#include "harness/reference/reference_image.h"
#include "harness/scene/gpu_scene.h"
#include "harness/scene/scene.h"
#include "ldm_impls/ldm_structure.h"

namespace ldm {

struct ReferenceSettings;

// What the measurement must provide before the pass can run.
struct PassRequirements {
  AttributeSet scene_attributes;  // uploaded besides positions
  FragmentPayload payload;        // stored by the structure per fragment besides depth
  bool needs_structure = true;    // false: the pass reads no LDM (a screen-space peer)
  bool runs_on_cpu = false;       // true: no GL work; timed by the CPU's wall clock (rtao)
};

// A sub-pass the pass times with ScopedSubpass; the frame loop attributes every other
// sub-pass of a frame to the structure's build (or to the raster baseline).
struct TimedSubpass {
  std::string name;         // as given to ScopedSubpass; the record's <name>_ms_* columns
  std::string description;  // one line, for `ldmbench columns`
  // false: only some frames or sizing policies run it (a rebuild, a census); ldmbench_gbench
  // times only the sub-passes every frame runs.
  bool every_frame = true;
};

// One output image; `name` becomes the file stem's suffix: <config_id>-<name>.exr.
struct PassImage {
  std::string name;
  Image image;
};

// A reference the scored (first) image is measured against, with the prefix of its record
// columns ("" for the pass's main reference: mse, ref_noise_mse, ...; "multi_" for e.g. the
// indirect pass's multi-bounce one: multi_mse, multi_ref_noise_mse, ...) and the exposure
// SSIM sees the images at (1 for AO; lighting: harness/reference/lighting_reference.h).
struct ScoredReference {
  std::string column_prefix;
  ReferenceResult reference;
  double ssim_exposure = 1.0;
};

// What prepare() is given. `ldm` and `structure` are null when the pass needs no structure.
struct PassInputs {
  const Scene& scene;
  const GpuScene& gpu_scene;
  const BuildInputs* ldm = nullptr;
  const LdmStructure* structure = nullptr;
  int width = 0, height = 0;
  // The configuration's value of every axis (harness/axes/axis.h: axis_real, axis_uint,
  // axis_text): where an axis declared for a pass reaches it, with no field of its own on
  // the way. Null where nothing measures a configuration (a pass prepared by hand).
  const AxisValues* axes = nullptr;
};

class Pass {
 public:
  virtual ~Pass() = default;

  virtual std::string name() const = 0;
  virtual PassRequirements requirements() const = 0;
  virtual std::vector<TimedSubpass> subpasses() const = 0;
  // The pass's effective settings for this scene that are not its parameters' own columns
  // (those pass_parameter_values() writes): the AO settings in effect (its parameters over
  // the scene's defaults), e.g. {"d_max", 1.5}, and the value in effect of a parameter that
  // has no declared default where none is given.
  virtual std::vector<std::pair<std::string, RecordValue>> describe(const Scene& scene) const = 0;

  // Compiles shaders and allocates targets. Throws UserError when it cannot run here.
  virtual void prepare(const PassInputs& in) = 0;
  // One frame of the pass, every sub-pass timed by `timer` (which may be null).
  virtual void render(GpuTimer* timer) = 0;
  // The images of the last render(); the first is the one scored against the reference.
  virtual std::vector<PassImage> images() const = 0;
  // Record fields computed from the last render() (e.g. AO's range of values); none by default.
  virtual std::vector<std::pair<std::string, RecordValue>> results() const { return {}; }
  // The pixels of the last render() where the camera sees a surface (one channel, 1 or 0:
  // covered_pixel_fraction's pixels), over which mse_covered, nrmse_covered and
  // mssim_covered are measured; empty (not measured) by default.
  virtual Image coverage() const { return {}; }
  // Settings that run but are known to give a biased image, one sentence each, for the
  // record's status_detail; none by default.
  virtual std::vector<std::string> warnings() const { return {}; }
  // Ways the last render() may be wrong that no check of the structure sees (a trace the
  // device may have cut short: harness/passes/trace_steps.h), one sentence each. A
  // non-empty answer makes the record invalid; none by default.
  virtual std::vector<std::string> problems() const { return {}; }
  // How far two renders of the same inputs may differ per image value, relative to the
  // larger of the two (0: bit for bit, the default): what the counting replay's images are
  // checked against the measured frames' with. Not 0 only where the image sums in an order
  // the device chooses (additive blending of primitives appended by atomics).
  virtual double image_order_tolerance() const { return 0.0; }
  // The counting replay's pass, prepared, takes the sizing state of the measured one (same
  // configuration) so that its first render needs no growth (the photon buffer); nothing
  // by default.
  virtual void continue_sizing_from(const Pass& /*measured*/) {}
  // Work the pass's own configured capacity dropped in the last render(), counted (e.g. the
  // indirect pass's photon-buffer overflow), one sentence; empty when nothing was dropped. A
  // non-empty answer makes the record lossy, as a structure's counted loss does.
  virtual std::string loss() const { return {}; }
  // The pass's own buffers (allocated, used by the last render()), for the record's
  // mem_<name>_* columns; none by default. A pass that reads no structure (hbao) lists its
  // targets, which are its bytes_allocated; an LDM pass's (the indirect pass's photons) are
  // recorded beside the structure's, not in bytes_allocated/_used (the structure's storage).
  virtual std::vector<BufferMemory> memory() const { return {}; }

  // The converged image the first output estimates, width x height, for this scene and the
  // pass's settings: from the cache under settings.cache_dir when an entry matches, else
  // rendered (and stored). Needs no GL context.
  virtual ReferenceResult reference(const Scene& scene, int width, int height,
                                    const ReferenceSettings& settings) const = 0;
  // Every reference the first image is scored against, the main one first with prefix "".
  // By default reference() alone at exposure 1.
  virtual std::vector<ScoredReference> references(const Scene& scene, int width, int height,
                                                  const ReferenceSettings& settings) const {
    return {{"", reference(scene, width, height, settings), 1.0}};
  }
};

// What every pass declares, written once so that one place says what every pass overrides
// (as LDM_STRUCTURE_DECLARATIONS does for the structures): its static declarations (registered in pass_registry.cpp's table), the
// overrides of Pass's pure virtual functions, and results(), which all six passes implement
// alike. The other optional overrides (coverage, warnings, problems, memory, loss, ...), the
// destructor and work_counters() (rtao counts nothing) follow the macro in the passes that
// have them.
#define LDM_PASS_DECLARATIONS(NAME)                                                        \
  /* The parameters it reads (--param, the AO axes it takes), declared (harness/axes). */  \
  static std::vector<AxisSpec> parameters();                                               \
  /* The record columns it writes (describe(), results(), its counts), declared. */        \
  static std::vector<ColumnSpec> columns();                                                \
                                                                                           \
  std::string name() const override { return NAME; }                                       \
  PassRequirements requirements() const override;                                          \
  std::vector<TimedSubpass> subpasses() const override;                                    \
  std::vector<std::pair<std::string, RecordValue>> describe(const Scene& scene)            \
      const override;                                                                      \
  void prepare(const PassInputs& in) override;                                             \
  void render(GpuTimer* timer) override;                                                   \
  std::vector<PassImage> images() const override;                                          \
  std::vector<std::pair<std::string, RecordValue>> results() const override;               \
  ReferenceResult reference(const Scene& scene, int width, int height,                     \
                            const ReferenceSettings& settings) const override

// What the pass registry holds of a pass (harness/passes/pass_registry.cpp): its name, its
// declared parameters and record columns, and how to make it from checked parameters.
struct PassRegistration {
  std::string name;
  std::function<std::vector<AxisSpec>()> parameters;
  std::function<std::vector<ColumnSpec>()> columns;
  std::function<std::unique_ptr<Pass>(StructureParams&)> make;
  // The work its shaders count in the counting replay (harness/measure/work_counters.h);
  // none when empty.
  std::function<std::vector<WorkCounter>()> work = {};
  // The sub-passes in which it reads the structure through the query API: the structure's
  // query counters are recorded under each (structure_query_work_counters()).
  std::vector<std::string> query_subpasses = {};
};
// Adds a pass beyond the built-in ones (a test's, or a plugin's) before anything reads the
// registry's derived lists (the axis registry, the record schema).
void register_pass(PassRegistration registration);

std::vector<std::string> pass_names();
// The parameters a pass declares (its --param PASS:KEY=VALUE and the AO axes it reads),
// owner set; throws UserError for an unknown name.
std::vector<AxisSpec> pass_parameters(const std::string& name);
// The record columns a pass declares (harness/records/columns.h): first its own parameters'
// (each parameter with a column declares it: parameter_column()), then its columns().
std::vector<ColumnSpec> pass_columns(const std::string& name);
ColumnSpec parameter_column(const AxisSpec& parameter);
bool has_parameter_column(const AxisSpec& parameter);
// The values of a pass's parameters' own columns (those parameter_column() declares) for one
// configuration, in declaration order: each the configuration's value (`values`, keys
// "PASS:KEY"), else its declared default (what the pass was handed), typed as its column (an
// integer, a real, a flag or text). measure_configuration() writes them after describe()'s
// fields: a pass writes none of them itself, save the value in effect of a parameter with
// no declared default and no value (the indirect pass's a = s, T_foot off), which this leaves
// out, and a value resolved at run time (rtao's threads 0: the cores it used, its results()).
std::vector<std::pair<std::string, RecordValue>> pass_parameter_values(const std::string& name,
                                                                       const AxisValues& values);
// The work counters a pass declares (none for a pass that counts nothing).
std::vector<WorkCounter> pass_work_counters(const std::string& name);
// The sub-passes in which a pass reads the structure (PassRegistration::query_subpasses).
std::vector<std::string> pass_query_subpasses(const std::string& name);
// Throws UserError for an unknown name (listing the known ones) or bad parameters; `params`
// should carry a context such as "--pass ao" for its messages.
std::unique_ptr<Pass> make_pass(const std::string& name, StructureParams params);

}  // namespace ldm
