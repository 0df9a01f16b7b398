#pragma once
// `ldmbench sweep FILE --memory-plan`: the memory of every configuration of a sweep, known
// from the untimed fragment census without building anything (issue 24: advise prunes
// configurations over a memory budget before measuring them).
//
// For a configuration that reads an LDM, plan_memory() does what a measured run does before
// its first frame (harness/measuring/measurement_session.cpp): the scene uploaded with what the
// pass needs, the LDM views, the census, the sizing plan, make_structure() and prepare().
// The sizes come from prepare() itself, never from a second copy of each structure's
// arithmetic. Under the census and previous_frame policies the storage then grows, as the
// first frame of a run grows it, to the census's needs through the structure's own fits()
// and resize(); the census policy's count buffer comes from the SizingDriver a run uses.
// No build, no frame, no pass render, no reference.
//
// A pass without a structure (hbao, rtao) is prepared alone, as a run prepares it; its
// bytes are those of its targets (Pass::memory()).
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "harness/run/run_command.h"
#include "harness/records/record.h"
#include "harness/scene/scene.h"
#include "ldm_impls/ldm_structure.h"

namespace ldm {

struct LdmSetup;

// One configuration's planned memory, as the row of memory-plan.csv.
struct MemoryPlanRow {
  // What is planned: its identity columns are its axes' (write_axis_columns), as a measured
  // record's.
  Configuration config;
  uint64_t fragments = 0;
  uint32_t max_depth_complexity = 0;
  uint64_t bytes_allocated = 0;  // what the record column bytes_allocated sums
  std::vector<BufferMemory> buffers;
  // A fixed array's k (0: not a fixed array) and whether it drops fragments (k < deepest).
  uint32_t k = 0;
  bool lossy = false;
  std::string status;  // planned, refused, not_applicable
  std::string status_detail;

  Record to_record() const;
};

// The bytes planned are those a measured run of the configuration records, under every
// sizing policy: oracle and budget size everything in prepare(); census and previous_frame
// grow once, in the first frame, to what the timed census or the first build's counters
// count, which on a static scene is what the untimed census counted, so the plan grows the
// storage to the same needs the same way; for a run of more than one build it then settles
// it as the second build does (LdmStructure::settle_after_first_build()).

// Plans configuration after configuration, reusing one census (scene upload, views,
// census) for every configuration that shares its geometry and sizing plan: a sweep over
// the structures takes one census per (scene, N, R_LDM, sizing). Needs a current GL context.
class MemoryPlanner {
 public:
  explicit MemoryPlanner(const std::map<std::string, Scene>& scenes);
  ~MemoryPlanner();
  MemoryPlanner(const MemoryPlanner&) = delete;
  MemoryPlanner& operator=(const MemoryPlanner&) = delete;

  // Never throws for a configuration the device cannot hold (a buffer over the storage
  // block, a budget too small): that is a row with status "refused" and the reason.
  MemoryPlanRow plan(const PlannedConfiguration& planned);

 private:
  MemoryPlanRow plan_structure(const Configuration& config, const RunSettings& settings, MemoryPlanRow row);
  MemoryPlanRow plan_peer(const Configuration& config, const RunSettings& settings, MemoryPlanRow row);
  const LdmSetup& setup_for(const Configuration& config);

  const std::map<std::string, Scene>& scenes_;
  std::map<std::string, std::unique_ptr<LdmSetup>> setups_;  // by geometry and sizing key
};

// The rows as CSV (records_to_csv's format: a header, quoted where needed).
std::string memory_plan_csv(const std::vector<MemoryPlanRow>& rows);

}  // namespace ldm
