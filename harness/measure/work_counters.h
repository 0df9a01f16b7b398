#pragma once
// Device-independent work: what a frame's sub-passes did, counted by the shaders themselves
// in an untimed counting replay (harness/measuring/measurement_session.h), never inside a measured
// frame.
//
// Each structure and pass declares its counters (WorkCounter: the sub-pass that counts, a
// name, a unit, whether the count is deterministic) beside the code that counts them; the
// declarations become the record's work_<subpass>_<name> columns (work_columns()). The
// shaders count through shaders/common/work_counters.glsl: work_add(name, n) for a total,
// work_sample(name, value) for one value of a per-query distribution. Compiled without
// LDM_WORK_COUNT (every timed program) both are empty macros, so the measured shaders carry
// no trace of counting.
//
// Attribution to sub-passes needs nothing in the shaders: the counting replay's GpuTimer
// tells a WorkCounterBuffer (a SubpassObserver) where each ScopedSubpass begins and ends, and
// it binds that sub-pass's block of the buffer at WORK_COUNTERS_BINDING; a counter's slot
// (WORK_<name>) is the same in every block.
#include <cstdint>
#include <map>
#include <memory>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "harness/gl/gl_objects.h"
#include "harness/gl/shader_program.h"
#include "harness/measure/gpu_timer.h"
#include "harness/records/columns.h"
#include "harness/records/record.h"

namespace ldm {

enum class WorkShape {
  Total,         // one sum over the sub-pass: work_<subpass>_<name>
  Distribution,  // one value per query (a ray, a list, a pixel): _mean, _p50, _p99, _max, _total
};

// Whether two runs of one configuration count the same: anything that depends on the order
// fragments or invocations arrive (an insertion's walk, probes while inserting, retries,
// failed compare-and-swaps) is not.
enum class WorkOrder { Deterministic, ArrivalDependent };

struct WorkCounter {
  std::string subpass;  // the ScopedSubpass name it is counted under ("construct", "ao")
  std::string name;     // the shader's work_add(name, ...) / work_sample(name, ...)
  WorkShape shape = WorkShape::Total;
  std::string unit;     // per counted item: "fragments", "bytes", "nodes"
  std::string description;
  WorkOrder order = WorkOrder::Deterministic;

  std::string column() const { return "work_" + subpass + "_" + name; }
  bool deterministic() const { return order == WorkOrder::Deterministic; }
};

// The record columns of `counters` (group "work"): one per total, five per distribution.
// Columns two owners declare (work_construct_fragments of several structures) are merged:
// deterministic only when every owner's is.
std::vector<ColumnSpec> work_columns(const std::vector<WorkCounter>& counters);
// The suffixes of a distribution's columns, in order.
const std::vector<std::string>& work_distribution_suffixes();

// Histogram of a distribution: values below kWorkExactBins exactly, larger ones by powers
// of two (their percentiles are the bucket's lower bound, within a factor of two).
inline constexpr uint32_t kWorkExactBins = 256;
inline constexpr uint32_t kWorkExactBits = 8;  // log2(kWorkExactBins)
inline constexpr uint32_t kWorkBins = kWorkExactBins + 32 - kWorkExactBits;

// One distribution's words: count (2), sum (2), max, the bins.
struct WorkDistributionStats {
  uint64_t count = 0, sum = 0;
  uint32_t max = 0, p50 = 0, p99 = 0;
  double mean() const { return count ? double(sum) / double(count) : 0.0; }
};
// The statistics of one distribution block (header + kWorkBins bins).
WorkDistributionStats work_distribution_stats(const uint32_t* words);
// The value at quantile q (0..1) of a histogram of kWorkBins bins holding `count` values.
uint32_t work_histogram_quantile(const uint32_t* bins, uint64_t count, double q);

// The driver's own counts per sub-pass (GL_ARB_pipeline_statistics_query, core in GL 4.6),
// recorded beside the shaders' own as work_<subpass>_gl_<statistic> where the driver has
// it. They are the driver's view, not the shaders': llvmpipe counts fragment shader
// invocations per rasterised block, helpers and discarded ones included, so they differ
// from the shaders' own `fragments` (docs/reference/work-counters.md).
struct PipelineStatistic {
  GLenum target;
  const char* name;  // the column's suffix after gl_
  const char* unit;
  const char* description;
};
const std::vector<PipelineStatistic>& pipeline_statistics();

// The counters of one frame on the GPU: a block per declared sub-pass (and one scratch block
// for work outside them), each with a slot per counter name.
class WorkCounterBuffer : public SubpassObserver {
 public:
  explicit WorkCounterBuffer(std::vector<WorkCounter> counters);
  ~WorkCounterBuffer() override;

  // LDM_WORK_COUNT, WORK_COUNTERS_BINDING, WORK_EXACT_* and a WORK_<name> slot per counter:
  // what a counting variant of a shader is compiled with.
  ShaderDefines defines() const;
  void clear();  // zeroes every block and binds the scratch block
  // SubpassObserver: bind the sub-pass's block (or the scratch block) for what follows.
  void subpass_begun(const std::string& subpass) override;
  void subpass_ended(const std::string& subpass) override;
  // Whether a sub-pass of this name (declared or not) began since clear().
  bool began(const std::string& subpass) const { return began_.count(subpass) != 0; }
  // Leave the counting's own GPU work (summing blended totals into the counters) out of the
  // driver's statistics of the running sub-pass: its queries end before it and begin again
  // after, both parts added to the sub-pass's sums. Calls pair up; nothing while no sub-pass
  // runs or the driver has no statistics.
  void pause_statistics();
  void resume_statistics();

  // The record fields of every declared counter whose sub-pass ran since clear()
  // (distributions of no samples are left out), and, in `problems`, sub-passes that counted
  // work without declaring it.
  std::vector<std::pair<std::string, RecordValue>> read(std::vector<std::string>* problems) const;

  const std::vector<WorkCounter>& counters() const { return counters_; }

 private:
  void bind_block(size_t block) const;
  void begin_statistics();
  void end_statistics();  // into the running block's sums
  std::vector<WorkCounter> counters_;
  // Pipeline statistics: one query per statistic, begun and ended with each declared
  // sub-pass, its result added to the sub-pass's sums (empty: the driver has none).
  std::vector<GLuint> statistic_queries_;
  std::vector<std::vector<uint64_t>> statistic_sums_;  // [block][statistic]
  std::map<std::string, uint32_t> slot_;        // counter name -> word offset in a block
  std::map<std::string, size_t> block_of_;      // sub-pass -> block index
  std::vector<std::string> undeclared_seen_;
  std::set<std::string> began_;                 // every sub-pass begun since clear()    // sub-passes begun that declare no counters
  std::vector<bool> ran_;                       // per block: begun since clear()
  uint32_t block_words_ = 0;                    // padded to the buffer offset alignment
  size_t scratch_ = 0;                          // the last block
  size_t running_ = 0;                          // the block of the running sub-pass
  bool in_subpass_ = false;                     // a sub-pass runs (begun, not ended)
  bool statistics_running_ = false;             // its queries are begun
  GlBuffer buffer_;
};

// While alive, every program built (build_program) is the counting variant: compiled with
// `defines` (LDM_WORK_COUNT and the slots). A scope rather than a flag threaded through each
// structure and pass, because every shader they build is to be counted, and building them
// is what prepare() already does: a second instance prepared inside the scope is the
// counting replay's.
class WorkCountingScope {
 public:
  // `blend_totals`: whether the LDM geometry pass's fragment stages may count their totals by
  // additive blending instead of atomics (ldm_impls/common/blended_work_counts.h); off, every
  // counting site is an atomic.
  // `counts`: the buffer counting (its statistics paused around the counting's own GPU work:
  // UncountedGpuWork); null: none to pause.
  explicit WorkCountingScope(const ShaderDefines& defines, bool blend_totals = true,
                             WorkCounterBuffer* counts = nullptr);
  ~WorkCountingScope();
  // Whether a scope is alive: what a pass prepares now is the counting replay's (a pass whose
  // counting needs more than its shaders' counting variants, such as a target to count
  // into, sets it up then).
  static bool active();
  // Whether the alive scope lets totals be counted by blending.
  static bool blending_totals();
  // A blended total reached the float value up to which its sums are exact: the counts of
  // this scope may be wrong, so the replay is run again with blending off. `where` names it.
  static void report_inexact_blend(const std::string& where);
  // What was reported while this scope was alive.
  const std::vector<std::string>& inexact_blends() const;
  WorkCountingScope(const WorkCountingScope&) = delete;
  WorkCountingScope& operator=(const WorkCountingScope&) = delete;
};

// While alive, the GPU work issued is the counting's own (a sum of blended totals into the
// counters), not the counted frame's: left out of the driver's pipeline statistics of the
// running sub-pass (WorkCounterBuffer::pause_statistics). Nothing outside a counting scope.
class UncountedGpuWork {
 public:
  UncountedGpuWork();
  ~UncountedGpuWork();
  UncountedGpuWork(const UncountedGpuWork&) = delete;
  UncountedGpuWork& operator=(const UncountedGpuWork&) = delete;

 private:
  WorkCounterBuffer* counts_;
};

}  // namespace ldm
