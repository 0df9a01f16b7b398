#include "harness/records/columns.h"

#include <algorithm>
#include <cstdio>
#include <sstream>

#include <nlohmann/json.hpp>

#include "harness/records/harness_columns.h"

namespace ldm {
namespace {

using namespace columns;

// What a configuration was measured on and whether it measures anything (issue 22;
// harness/measuring/scene_profile.h, the trace step counts of the LDM passes): kept apart so that
// the main list stays as it was.
std::vector<ColumnSpec> scene_profile_columns() {
  return {
      kSceneRadius,
      kSceneOriginOffset,
      kFarFileVertices,
      kCollapsedTriangles,
      kCameraSource,
      kLightSource,
      kDMaxSource,
      kDepthP50,
      kDepthP90,
      kDepthP99,
      kDepthHistogram,
      kDepthShareAboveK,
      kCoveredPixelFraction,
      kDMaxLdmPixels,
      kTraceStepsMax,
      kTraceStepsBound,
      kLoopIterationLimit,
      kDegenerate,
  };
}

std::vector<ColumnSpec> main_columns();

}  // namespace

const std::vector<ColumnSpec>& harness_record_columns() {
  static const std::vector<ColumnSpec> columns = [] {
    std::vector<ColumnSpec> all = main_columns();
    for (auto& column : scene_profile_columns()) all.push_back(std::move(column));
    return all;
  }();
  return columns;
}

namespace {

std::vector<ColumnSpec> main_columns() {
  return {
      kConfigId,
      kStatus,
      kStatusDetail,
      kScene,
      kStructure,
      kPass,
      kNViews,
      kRLdm,
      kWidth,
      kHeight,
      kStructureParams,
      kSizingPolicy,
      kFrames,
      kWarmup,
      kLdmbenchVersion,
      kGitCommit,
      kShaderDir,
      kDevice,
      kDeviceId,
      kGlDriver,
      kGlVendor,
      kGlVersion,
      kEglPlatform,
      kInt64Atomics,
      kDriverDefects,
      kTimer,
      kHost,
      kSlurmJobId,
      kSlurmArrayJobId,
      kSlurmArrayTaskId,
      kSlurmNode,
      kSlurmGpus,
      kSceneName,
      kSceneHash,
      kTriangles,
      kSceneAttributes,
      kSceneGpuBytes,
      kPayload,
      kFragments,
      kMaxDepthComplexity,
      kMeanDepthComplexity,
      kNonemptyPixelFraction,
      kFragmentsStored,
      kFragmentsLost,
      kOverflow,
      kTiedDepths,
      kChecksumChanges,
      kListsChecksum,
      kVerifyMode,
      kVerifyStride,
      kVerifyFullChecks,
      kVerifySampledChecks,
      kVerifySampledPixels,
      kCounterNamePattern,
      kSizingKeyPattern,
      kSizingRebuilds,
      kSizingRebuildsMeasured,
      kSizingReallocations,
      kRepetitions,
      kRepetition,
      kFramesMeasured,
      kFramesPerRepetition,
      kTimeTarget,
      kTimeTargetEffective,
      kTimeCapS,
      kTimeClockWarmupS,
      kTimeTargetMet,
      kTimeInterval,
      kTimeHalfWidthWithinRun,
      kTimeRunToRunSpread,
      kTimeCalibration,
      kLoadAverageEndPattern,
      kCpuGovernor,
      kCpuMhzEndPattern,
      kGpuSmClockMhzEndPattern,
      kGpuSmClockMaxMhz,
      kClockWarmupFrames,
      kClockWarmupSeconds,
      kGpuPowerWEndPattern,
      kGpuThrottleReasonsEndPattern,
      kTimeIntervalCoverage,
      kTimeHalfWidth,
      kSubpassMsMedianPattern,
      kSubpassMsCiLowPattern,
      kSubpassMsCiHighPattern,
      kSubpassMsRepSpreadPattern,
      kSubpassMsMinPattern,
      kSubpassMsMaxPattern,
      kSubpassMsStddevPattern,
      kBuildVsRaster,
      kBuildVsRasterTouch,
      kBaselineFrames,
      kRasterTouchFragments,
      kFragmentsPerSecond,
      kFrameSamplesCsv,
      kFramesTimedMs,
      kVerifyMs,
      kVerifyWarmupMs,
      kWorkReplayMs,
      kVerifyShare,
      kWallSeconds,
      kMemBufferAllocatedPattern,
      kMemBufferUsedPattern,
      kBytesAllocated,
      kBytesUsed,
      kRefSpp,
      kRefNoiseMse,
      kRefNoiseMssim,
      kRefNoiseTargetMet,
      kRefRenderSeconds,
      kRefFromCache,
      kRefCacheKey,
      kRefRayOffset,
      kRefRayOffsetOk,
      kMse,
      kNrmse,
      kPsnr,
      kMssim,
      kMseCovered,
      kNrmseCovered,
      kMssimCovered,
      kSsimExposure,
      kMseOverNoise,
      kBias,
      kBiasShare,
      kMeanRatio,
      kMeanRatioSe,
      kMetricsError,
      kMultiRefRenderSeconds,
      kMultiRefFromCache,
      kMultiColumnPattern,
      kImageExr,
      kImagePng,
      kImageNameExrPattern,
      kImageNamePngPattern,
      kReferenceExr,
      kSsimMapPng,
      kDiffPng,
      kDiffPngMax,
  };
}

}  // namespace

namespace {

bool matches(const std::string& pattern, const std::string& column) {
  const auto open = pattern.find('<');
  if (open == std::string::npos) return pattern == column;
  const auto close = pattern.find('>', open);
  const std::string prefix = pattern.substr(0, open), suffix = pattern.substr(close + 1);
  return column.size() > prefix.size() + suffix.size() && column.starts_with(prefix) &&
         column.ends_with(suffix);
}

}  // namespace

const ColumnSpec* find_column_in(const std::vector<ColumnSpec>& columns, const std::string& column) {
  for (const auto& c : columns)
    if (c.name == column) return &c;
  for (const auto& c : columns)
    if (matches(c.name, column)) return &c;
  return nullptr;
}

const std::vector<ColumnLabel>& column_labels() {
  using namespace columns;
  // The label and scale of a headline column; which way is better is the column's own.
  const auto label = [](const Column& c, const char* text, double scale = 1.0) {
    return ColumnLabel{c.name, text, int(c.better), scale};
  };
  constexpr double kMiB = 1.0 / (1024.0 * 1024.0);
  static const std::vector<ColumnLabel> labels = {
      label(kConfigId, "configuration"),
      label(kStatus, "status"),
      {"build_ms_median", "build ms", int(kSubpassMsMedianPattern.better)},
      {"pass_ms_median", "pass ms", int(kSubpassMsMedianPattern.better)},
      {"frame_ms_median", "frame ms", int(kSubpassMsMedianPattern.better)},
      label(kBytesAllocated, "MiB allocated", kMiB),
      label(kBytesUsed, "MiB used", kMiB),
      label(kMse, "MSE"),
      label(kNrmse, "NRMSE"),
      label(kMssim, "MSSIM"),
      label(kMseCovered, "MSE covered"),
      label(kNrmseCovered, "NRMSE covered"),
      label(kMssimCovered, "MSSIM covered"),
      label(kMseOverNoise, "MSE / ref noise"),
      label(kRefNoiseMse, "ref noise MSE"),
      label(kCoveredPixelFraction, "covered share"),
  };
  return labels;
}

const ColumnLabel& column_label(const std::string& column) {
  for (const auto& l : column_labels())
    if (l.column == column) return l;
  static thread_local ColumnLabel unnamed;
  unnamed = {column, column};
  return unnamed;
}

std::string column_heading(const std::string& column) {
  const ColumnLabel& l = column_label(column);
  return l.label + (l.better < 0 ? " ↓" : l.better > 0 ? " ↑" : "");
}

std::string column_labels_json() {
  std::ostringstream out;
  out << "{\n  \"arrows\": {\"lower\": \"↓\", \"higher\": \"↑\"},\n  \"columns\": [\n";
  const auto& labels = column_labels();
  for (size_t i = 0; i < labels.size(); ++i) {
    char scale[32];
    std::snprintf(scale, sizeof scale, "%.17g", labels[i].scale);
    out << "    {\"column\": \"" << labels[i].column << "\", \"label\": \"" << labels[i].label
        << "\", \"better\": " << labels[i].better << ", \"scale\": " << scale << "}"
        << (i + 1 < labels.size() ? "," : "") << "\n";
  }
  out << "  ]\n}\n";
  return out.str();
}

std::string columns_markdown(const std::vector<ColumnSpec>& columns) {
  std::ostringstream out;
  out << "| group | column | unit | description |\n| --- | --- | --- | --- |\n";
  std::string group;
  for (const auto& c : columns) {
    out << "| " << (c.group == group ? "" : c.group) << " | `" << c.name << "` | " << c.unit
        << " | " << c.description << " |\n";
    group = c.group;
  }
  return out.str();
}

std::string columns_text(const std::vector<ColumnSpec>& columns) {
  size_t width = 0;
  for (const auto& c : columns) width = std::max(width, c.name.size());
  std::ostringstream out;
  std::string group;
  for (const auto& c : columns) {
    if (c.group != group) out << (group.empty() ? "" : "\n") << c.group << ":\n";
    group = c.group;
    out << "  " << c.name << std::string(width + 2 - c.name.size(), ' ')
        << (c.unit.empty() ? "" : "[" + c.unit + "] ") << c.description << "\n";
  }
  return out.str();
}

const char* column_kind_name(ColumnKind kind) {
  switch (kind) {
    case ColumnKind::Number: return "number";
    case ColumnKind::Text: return "text";
    case ColumnKind::Flag: return "flag";
    case ColumnKind::Mixed: break;
  }
  return "mixed";
}

std::string columns_json(const std::vector<ColumnSpec>& columns) {
  nlohmann::ordered_json list = nlohmann::ordered_json::array();
  for (const auto& c : columns)
    list.push_back({{"group", c.group},
                    {"name", c.name},
                    {"unit", c.unit},
                    {"description", c.description},
                    {"kind", column_kind_name(c.kind)},
                    {"varies_between_runs", c.varies_between_runs},
                    {"deterministic", c.deterministic},
                    {"summed_in_arrival_order", c.summed_in_arrival_order},
                    {"better", c.better == Better::Lower    ? "lower"
                               : c.better == Better::Higher ? "higher"
                                                            : "neither"}});
  nlohmann::ordered_json root;
  root["columns"] = list;
  return root.dump(2) + "\n";
}

}  // namespace ldm
