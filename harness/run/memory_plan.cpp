#include "harness/run/memory_plan.h"

#include "harness/settings/harness_axes.h"
#include "harness/measuring/ldm_setup.h"
#include "harness/passes/pass.h"
#include "harness/records/harness_columns.h"
#include "harness/scene/gpu_scene.h"
#include "harness/util/error.h"
#include "ldm_impls/common/sizing_driver.h"
#include "ldm_impls/common/storage_fit.h"

namespace ldm {
namespace {

// A sweep over structures and parameters reuses one census per key; a few geometries are
// kept at once (each holds a census's per-pixel counts and the scene on the GPU).
constexpr size_t kCachedSetups = 8;

uint64_t sum_allocated(const std::vector<BufferMemory>& buffers) {
  uint64_t total = 0;
  for (const auto& b : buffers) total += b.allocated;
  return total;
}

std::string buffers_text(const std::vector<BufferMemory>& buffers) {
  std::string text;
  for (const auto& b : buffers)
    text += (text.empty() ? "" : ";") + b.name + "=" + std::to_string(b.allocated);
  return text;
}

// A fixed array reports its k among its sizing() entries; other structures have none.
uint32_t fixed_array_k(const LdmStructure& structure) {
  for (const auto& [key, value] : structure.sizing())
    if (key == "k") return uint32_t(std::stoul(value));
  return 0;
}

// What a measured run's first frame does to the storage under a policy that grows it
// (ldm_impls/common/sizing_strategy.cpp): census grows it to the timed census's count,
// previous_frame to what the first build's own counters needed, and the DF-buffer grows
// itself to its scan total. On a static scene each of those is the census's count, so the
// storage is grown to the census's needs through the structure's own fits() and resize().
void grow_as_first_frame(LdmStructure& structure, const SizingPlan& plan, const FragmentCensus& census) {
  const SizingStrategy& strategy = plan.strategy();
  if (!strategy.counts_every_frame() && !strategy.grows_from_counters()) return;
  const SizingNeeds needs = census_needs(census);
  if (!structure.fits(needs)) structure.resize(needs);
}

std::unique_ptr<Pass> make_configuration_pass(const Configuration& config) {
  return make_pass(config.pass, StructureParams(config.pass_params, "--pass " + config.pass));
}

MemoryPlanRow refused(MemoryPlanRow row, const std::string& why) {
  row.status = "refused";
  row.status_detail = why;
  row.bytes_allocated = 0;
  row.buffers.clear();
  return row;
}

}  // namespace


Record MemoryPlanRow::to_record() const {
  using namespace columns;
  Record r;
  r.set(kConfigId, config.id());
  // The swept axes' columns: the run-wide image size and frames are not the plan's.
  write_axis_columns(r, config, AxisColumns::Listed);
  r.set(kFragments, fragments);
  r.set(kMaxDepthComplexity, max_depth_complexity);
  // A refused configuration allocates nothing, which a budget filter must not read as 0 bytes.
  if (status == "refused")
    r.put(kBytesAllocated.name, std::monostate{});
  else
    r.set(kBytesAllocated, bytes_allocated);
  r.set("buffers", buffers_text(buffers));
  // Blank where it does not apply (not a fixed array), so that no one reads "false" as a verdict.
  if (k) {
    r.set("k", k);
    r.set("lossy", lossy);
  } else {
    r.put("k", std::monostate{});
    r.put("lossy", std::monostate{});
  }
  r.set(kStatus, status);
  r.set(kStatusDetail, status_detail);
  return r;
}

std::string memory_plan_csv(const std::vector<MemoryPlanRow>& rows) {
  std::vector<Record> records;
  for (const auto& row : rows) records.push_back(row.to_record());
  if (records.empty()) records.push_back(MemoryPlanRow().to_record());  // the header alone
  std::string csv = records_to_csv(records);
  if (rows.empty()) csv.erase(csv.find('\n') + 1);
  return csv;
}

MemoryPlanner::MemoryPlanner(const std::map<std::string, Scene>& scenes) : scenes_(scenes) {}
MemoryPlanner::~MemoryPlanner() = default;

MemoryPlanRow MemoryPlanner::plan(const PlannedConfiguration& planned) {
  const Configuration& config = planned.config;
  MemoryPlanRow row;
  row.config = config;
  try {
    if (config.structure == kNoStructure) return plan_peer(config, planned.settings, row);
    return plan_structure(config, planned.settings, row);
  } catch (const std::exception& e) {
    // As a sweep records a configuration that throws as failed and goes on.
    return refused(row, e.what());
  }
}

const LdmSetup& MemoryPlanner::setup_for(const Configuration& config) {
  const PassRequirements needs = make_configuration_pass(config)->requirements();
  const SizingSettings& sizing = config.sizing;
  const std::string key = config.scene + "|" + std::to_string(config.views) + "|" +
                          std::to_string(config.resolution) + "|" + needs.scene_attributes.describe() +
                          "|" + needs.payload.describe() + "|" + sizing_policy_name(sizing.policy) +
                          "|" + std::to_string(sizing.budget_bytes) + "|" +
                          std::to_string(sizing.initial_per_pixel);
  auto found = setups_.find(key);
  if (found != setups_.end()) return *found->second;
  if (setups_.size() >= kCachedSetups) setups_.clear();
  auto setup = std::make_unique<LdmSetup>(scenes_.at(config.scene), needs.scene_attributes,
                                          config.views, config.resolution, needs.payload, sizing);
  return *setups_.emplace(key, std::move(setup)).first->second;
}

MemoryPlanRow MemoryPlanner::plan_structure(const Configuration& config, const RunSettings& settings,
                                            MemoryPlanRow row) {
  const LdmSetup& setup = setup_for(config);
  const FragmentCensus& census = setup.census;
  row.fragments = census.total_fragments;
  row.max_depth_complexity = census.max_depth_complexity;
  try {
    // What MeasurementSession does before its first frame, then what that frame grows.
    std::unique_ptr<LdmStructure> structure = setup.prepare(config.structure, config.params);
    grow_as_first_frame(*structure, setup.sizing, census);
    // A run of more than one build records the storage its later builds keep.
    if (settings.warmup + settings.frames > 1) structure->settle_after_first_build();
    row.buffers = structure->memory();
    // The policy's own buffers (the census policy's counts), as the record sums them.
    const SizingDriver sizer(*structure, *setup.inputs);
    for (const auto& buffer : sizer.memory()) row.buffers.push_back(buffer);
    row.k = fixed_array_k(*structure);
  } catch (const StorageBlockExceeded& e) {  // what a run's failed record says
    return refused(row, explained_refusal(e, census, config.views, config.resolution).what());
  } catch (const std::exception& e) {  // e.g. a budget that does not hold the fixed buffers
    return refused(row, e.what());
  }
  row.bytes_allocated = sum_allocated(row.buffers);
  row.lossy = row.k && row.k < census.max_depth_complexity;
  row.status = "planned";
  return row;
}

MemoryPlanRow MemoryPlanner::plan_peer(const Configuration& config, const RunSettings& settings,
                                       MemoryPlanRow row) {
  // As MeasurementSession prepares a peer: the scene as given, what the pass asks for
  // uploaded, the pass prepared at the image size; its targets are its memory.
  std::unique_ptr<Pass> pass = make_configuration_pass(config);
  const Scene& scene = scenes_.at(config.scene);
  const GpuScene gpu_scene(scene, pass->requirements().scene_attributes);
  pass->prepare({scene, gpu_scene, nullptr, nullptr, settings.width, settings.height});
  row.buffers = pass->memory();
  row.bytes_allocated = sum_allocated(row.buffers);
  row.status = "planned";
  return row;
}

}  // namespace ldm
