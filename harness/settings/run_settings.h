#pragma once
// What `ldmbench run` measures: the axes of a sweep (every combination is one configuration,
// one record) and the settings shared by all of them.
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "harness/axes/axis.h"
#include "harness/gl/egl_context.h"
#include "harness/measure/frame_stop_rule.h"
#include "harness/reference/reference_settings.h"
#include "harness/scene/ao_variants.h"
#include "ldm_impls/common/sizing.h"

namespace ldm {

enum class Visibility { Scene, Attenuated, Unattenuated };

// What keeps the repetitions of a configuration independent (harness/measuring/repetitions.h):
// a fresh GL context per round in this process, or a process of its own per repetition.
enum class RepetitionIsolation { Context, Process };
const char* repetition_isolation_name(RepetitionIsolation isolation);
RepetitionIsolation parse_repetition_isolation(const std::string& name);  // context | process

struct RunSettings {
  // Axes.
  std::vector<std::string> scenes = {"cornell"};
  std::vector<std::string> structures = {"psppsll"};
  std::vector<std::string> passes = {"ao"};
  std::vector<uint32_t> views = {32};
  std::vector<uint32_t> resolutions = {128};
  std::vector<float> d_max;  // empty: the scene's own
  std::vector<Visibility> visibility = {Visibility::Scene};
  std::vector<AoTrace> traces = {kDefaultAoTrace};
  std::vector<AoEstimatorChoice> estimators = {AoEstimatorChoice::Eq13};
  // How structures learn their sizes (ldm_impls/common/sizing.h). The default charges every
  // structure for what it needs to know: see docs/reference/structures.md.
  std::vector<SizingPolicy> sizing = {SizingPolicy::PreviousFrame};
  double sizing_budget_mib = 0;         // budget: required with --sizing budget
  uint32_t sizing_initial_per_pixel = 1;  // previous_frame's first guess
  // structure name -> key -> value (--param ppfla:k=4)
  std::map<std::string, std::map<std::string, std::string>> structure_params;
  // Shared.
  std::optional<float> normal_offset_pixels;  // empty: the scene's own
  int width = 256, height = 256;
  // Measured frames: at least `frames` per repetition, more until `precision` is met
  // (harness/measure/frame_stop_rule.h); warm-up frames before them are judged, not timed.
  int frames = 5, warmup = 2;
  TimePrecision precision;
  // Independent repetitions of every configuration, each in a fresh GL context, measured
  // round robin over the configurations (harness/measuring/repetitions.h).
  int repetitions = 1;
  RepetitionIsolation isolation = RepetitionIsolation::Context;
  bool write_images = true;
  // The untimed counting replay after each configuration's measured frames (the work_*
  // columns, harness/measure/work_counters.h); off only to measure what it costs.
  bool count_work = true;
  std::string out_dir;  // empty: results/runs/<timestamp>
  bool overwrite = false;  // replace another sweep's results in out_dir (else refuse)
  bool redo_failed = false;  // resuming: measure again what out_dir holds as failed
  // Invocation, not measurement: measure only the next repetition of this configuration
  // (a child of --isolation process or of `ldmbench interleave`), the session it belongs
  // to, and listing the configurations instead of measuring them.
  std::string step;
  std::string calibration;  // --calibration auto|skip|FILE; "" = LDM_CALIBRATION, else auto
  std::string interleaved_session;
  bool dry_run = false;
  ContextOptions context = default_context_options();
  // The values of axes declared without a binding to a field here (harness/settings/harness_axes.h),
  // canonical, by key.
  std::map<std::string, std::vector<std::string>> axis_lists;
  std::string timer = "auto";  // auto | gl_timestamp | fenced_wall_clock
  std::string verify = "sampled";  // every | sampled (ldm_impls/common/build_verifier.h)
  ReferenceSettings reference;
};

// The structure of a configuration whose pass reads no LDM (Pass requirements).
inline constexpr const char* kNoStructure = "none";

// AxisValues: one configuration's value of every axis (harness/axes/axis.h).

struct Configuration {
  std::string scene;  // spec as given (name or path)
  std::string structure;
  std::string pass;
  uint32_t views = 0;
  uint32_t resolution = 0;
  int width = 0, height = 0;  // the output image (image_size)
  std::optional<float> d_max;
  Visibility visibility = Visibility::Scene;
  AoTrace trace = kDefaultAoTrace;
  AoEstimatorChoice estimator = AoEstimatorChoice::Eq13;
  std::map<std::string, std::string> params;
  // The pass's parameters (harness/passes/pass.h): the AO axes of the command line
  // (--d-max, --visibility, --normal-offset, --trace, --ao-estimator) as key=value, checked
  // by the pass itself.
  std::map<std::string, std::string> pass_params;
  SizingSettings sizing;
  // Every axis's value (the fields above are typed views of it): what identifies the
  // configuration.
  AxisValues values;
  // A short unique name for file names, made of the axes' id fragments
  // (harness/settings/harness_axes.cpp):
  // cornell-psppsll-ao-n32-r128[-d1.5][-att][-off<px>]-<trace>[-normalized][-k=v...]-<sizing>,
  // sizing one of oracle, census, prevframe[-guessG] (G != 1), budget<MiB>, then -img<W>x<H>
  // and -f<F>w<W> when a sweep varies them; for a pass that reads no LDM only what applies:
  // cornell-none-hbao[-d1.5][-att][-k=v...]
  const std::string& id() const { return id_; }
  std::string id_;
};

std::vector<Configuration> expand_configurations(const RunSettings& settings);
std::string visibility_name(Visibility v);

}  // namespace ldm
