#include "ldm_impls/dfbuffer/dfbuffer.h"
#include "ldm_impls/common/sizing_strategy.h"

#include <algorithm>

#include "harness/gl/bindings.h"
#include "ldm_impls/common/compute_grid.h"
#include "ldm_impls/common/list_node_pool.h"
#include "ldm_impls/common/post_sort.h"
#include "ldm_impls/common/structure_counters.h"

namespace ldm {

namespace {
constexpr uint64_t kPixelGroupSize = 64;  // local_size_x of sort.comp and unfilled.comp
constexpr uint32_t kBindingCounts = kStructureBinding0;  // shaders/ldm/dfbuffer/layout.glsl
constexpr uint32_t kBindingOffsets = kStructureBinding0 + 1;
constexpr uint32_t kBindingDepths = kStructureBinding0 + 2;
constexpr uint32_t kBindingCheck = kStructureBinding0 + 3;  // unfilled.comp
constexpr uint64_t kCounterWords = 4;
constexpr uint64_t kUnfilledWord = 3;
}  // namespace

DfBuffer::DfBuffer(StructureParams& params) { requested_local_ = read_sort_local_param(params); }

// A data table of its own counters, alike in form only to the other structures' (see
// ldm_impls/common/structure_counters.h).
std::vector<WorkCounter> DfBuffer::work_counters() {
  std::vector<WorkCounter> own = {
      // shaders/ldm/dfbuffer/count.frag
      {"count", "atomic_add", WorkShape::Total, "atomics", "count: DF-buffer atomicAdd on a pixel's count (one per fragment)"},
      // scan_blocks.comp and scan_add.comp, every level
      {"prefix_sum", "invocations", WorkShape::Total, "invocations",
       "prefix_sum: compute invocations of the scan's dispatches (every level, scan and uniform add)"},
      bytes_loaded("prefix_sum", "counts", "counts read (4 bytes per pixel)"),
      bytes_loaded("prefix_sum", "offsets",
          "offsets read by the uniform add (4 bytes per value of the blocks after the first)"),
      bytes_stored("prefix_sum", "offsets",
          "offsets written (the scan's pixels + 1, and again by the uniform add)"),
      bytes_loaded("prefix_sum", "scan_block_sums",
          "block sums read (higher levels' scans, the uniform add's block offsets)"),
      bytes_stored("prefix_sum", "scan_block_sums",
          "block sums written (each block's sum, higher levels' scans and uniform adds)"),
      // build.frag
      {"construct", "atomic_add", WorkShape::Total, "atomics",
       "construct: DF-buffer atomicAdd decrementing a pixel's count (one per fragment) and "
       "atomic counter increments of lost fragments"},
      bytes_loaded("construct", "offsets",
          "DF-buffer offsets read (8 bytes per fragment: the pixel's and the next)"),
      bytes_stored("construct", "depths", "DF-buffer depths written (4 bytes per fragment stored)"),
  };
  // sort.comp with ldm/common/post_sort.glsl and heap_sort.glsl
  const std::vector<WorkCounter> sort = post_sort_work_counters({
      bytes_loaded("sort", "offsets", "DF-buffer offsets read (8 bytes per pixel)"),
      bytes_loaded("sort", "depths",
          "DF-buffer depths copied into the local array (4 bytes each; ranges of 2 up to local)"),
      bytes_stored("sort", "depths", "DF-buffer depths written back from the local array (4 bytes each)"),
      bytes_loaded("sort", "depths_heap",
          "DF-buffer depths the heap sort in place read (ranges longer than local)", kArrival),
      bytes_stored("sort", "depths_heap", "DF-buffer depths the heap sort in place wrote", kArrival),
  });
  own.insert(own.end(), sort.begin(), sort.end());
  return with_geometry_counters({"count", "construct"}, own);
}

// shaders/ldm/dfbuffer/query.glsl: a query is one ldm_begin or ldm_next; the ranges are
// sorted whatever the order of arrival, so every count is deterministic.
std::vector<WorkCounter> DfBuffer::query_work_counters() {
  return {
      ListNodePool::nodes_visited_counter(),
      bytes_loaded("", "offsets", "DF-buffer offsets its queries read (8 bytes per ldm_begin)"),
      bytes_loaded("", "depths", "DF-buffer depths its queries read (4 bytes per ldm_depth)"),
  };
}

std::vector<AxisSpec> DfBuffer::parameters() { return {sort_local_parameter()}; }

void DfBuffer::prepare(const BuildInputs& in) {
  plan_ = in.sizing;
  pixels_ = in.views.views().total_pixels();
  local_ = sort_local_size(requested_local_, plan_);
  const auto words = [](uint64_t n) { return n * sizeof(uint32_t); };
  counts_ = GlBuffer("counts", checked_storage_block("dfbuffer", "counts", words(pixels_)));
  offsets_ = GlBuffer("offsets", checked_storage_block("dfbuffer", "offsets", words(pixels_ + 1)));
  counters_ = GlBuffer("counters", words(kCounterWords));
  scan_ = std::make_unique<PrefixSum>(pixels_);
  fragments_ = &in.fragments;
  base_defines_ = common_structure_defines(in);
  count_program_ = in.fragments.build_program("ldm/dfbuffer/count.frag", base_defines_);
  if (plan_.strategy().fixed_by_budget()) {
    const uint64_t fixed = counts_.bytes() + offsets_.bytes() + scan_->scratch_bytes() +
                           counters_.bytes();
    allocate_depths(budget_after("dfbuffer", plan_, fixed) / sizeof(uint32_t));
  } else {
    allocate_depths(plan_.initial.fragments);
  }
}

void DfBuffer::allocate_depths(uint64_t capacity) {
  capacity_ = capacity;
  // A zero-sized buffer cannot be created; an empty scene still gets one (unused) slot.
  const uint64_t depth_words = std::max<uint64_t>(1, capacity_);
  depths_ = GlBuffer("depths", checked_storage_block("dfbuffer", "depths",
                                                     depth_words * sizeof(uint32_t)));
  // The capacity is a compile-time constant of the storing, sorting and query shaders.
  ShaderDefines defines = base_defines_;
  defines.set("LDM_DF_CAPACITY", std::to_string(capacity_) + "u");
  query_defines_ = defines;
  build_program_ = fragments_->build_program("ldm/dfbuffer/build.frag", defines);
  unfilled_program_ = build_compute_program("ldm/dfbuffer/unfilled.comp", defines);
  defines.set("LDM_SORT_LOCAL", std::to_string(local_) + "u");
  sort_program_ = build_compute_program("ldm/dfbuffer/sort.comp", defines);
  query_defines_changed();
}

uint64_t DfBuffer::read_scan_total() const {
  uint32_t scan_total = 0;
  offsets_.download(&scan_total, sizeof scan_total, pixels_ * sizeof(uint32_t));
  return scan_total;
}

SizingNeeds DfBuffer::needed() {
  const uint64_t total = read_scan_total();
  return {total, 0, total > capacity_};
}

bool DfBuffer::fits(const SizingNeeds& needs) const {
  return plan_.strategy().fixed_by_budget() || needs.fragments <= capacity_;
}

void DfBuffer::resize(const SizingNeeds& needs) {
  if (!fits(needs)) allocate_depths(needs.fragments);
}

void DfBuffer::clear(GpuTimer* timer) {
  // The storing pass leaves every count at 0 (§3.2.10), but a build that went wrong does
  // not, so the counts are cleared anyway. The depths are not: the storing pass writes every
  // slot, and stats() counts any slot that it did not ("unfilled_slots").
  ScopedSubpass timed(timer, "clear");
  counts_.clear_to_zero();
  counters_.clear_to_zero();
}

void DfBuffer::count(const BuildInputs& in, GpuTimer* timer) {
  ScopedSubpass timed(timer, "count");
  counts_.bind_storage(kBindingCounts);
  in.fragments.run(count_program_);
}

void DfBuffer::prefix_sum(GpuTimer* timer) {
  ScopedSubpass timed(timer, "prefix_sum");
  scan_->run(counts_, offsets_);
}

void DfBuffer::construct(const BuildInputs& in, GpuTimer* timer) {
  ScopedSubpass timed(timer, "construct");
  counts_.bind_storage(kBindingCounts);
  offsets_.bind_storage(kBindingOffsets);
  depths_.bind_storage(kBindingDepths);
  counters_.bind_atomic_counter(kStructureCounterBinding);
  in.fragments.run(build_program_);
}

void DfBuffer::sort(GpuTimer* timer) {
  ScopedSubpass timed(timer, "sort");
  offsets_.bind_storage(kBindingOffsets);
  depths_.bind_storage(kBindingDepths);
  counters_.bind_atomic_counter(kStructureCounterBinding);
  run_linear_compute(sort_program_, pixels_, kPixelGroupSize,
                     GL_SHADER_STORAGE_BARRIER_BIT | GL_ATOMIC_COUNTER_BARRIER_BIT |
                         GL_BUFFER_UPDATE_BARRIER_BIT);
}

void DfBuffer::build(const BuildInputs& in, GpuTimer* timer) {
  clear(timer);
  count(in, timer);
  prefix_sum(timer);
  if (plan_.strategy().counts_every_frame()) {
    // The count pass and scan are this structure's census: the scan total, read back (a
    // sync), sizes the depth array before the storing pass, growing it when needed.
    SizingNeeds needs;
    {
      ScopedSubpass timed(timer, "readback");
      needs = needed();
    }
    if (!fits(needs)) {
      ScopedSubpass timed(timer, "reallocate");
      resize(needs);
    }
  }
  construct(in, timer);
  sort(timer);
}

uint64_t DfBuffer::count_unfilled_slots() const {
  const uint32_t zero = 0;
  glClearNamedBufferSubData(counters_.id(), GL_R32UI, GLintptr(kUnfilledWord * sizeof(uint32_t)),
                            sizeof(uint32_t), GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
  counts_.bind_storage(kBindingCounts);
  counters_.bind_storage(kBindingCheck);
  run_linear_compute(unfilled_program_, pixels_, kPixelGroupSize, GL_BUFFER_UPDATE_BARRIER_BIT);
  uint32_t unfilled = 0;
  counters_.download(&unfilled, sizeof unfilled, kUnfilledWord * sizeof(uint32_t));
  return unfilled;
}

BuildStats DfBuffer::stats() const {
  const uint64_t scan_total = read_scan_total();
  uint32_t c[kCounterWords] = {};
  counters_.download(c, sizeof c);
  const uint64_t lost_beyond_count = c[0], lost_beyond_capacity = c[1];
  const uint64_t unfilled = count_unfilled_slots();
  // The count pass saw scan_total fragments; of their slots, `unfilled` found no fragment in
  // the storing pass and lost_beyond_capacity lay past the array. The storing pass saw the
  // rest plus the fragments that found their pixel's range already used up.
  BuildStats s;
  s.fragments_rasterized = scan_total - unfilled + lost_beyond_count;
  s.fragments_stored = scan_total - unfilled - lost_beyond_capacity;
  s.fragments_lost = lost_beyond_count + lost_beyond_capacity;
  s.overflow = scan_total > capacity_;
  s.counters = {{"lists_sorted_in_place", double(c[2])},
                {"scan_total", double(scan_total)},
                {"storage_mismatch", scan_total != capacity_ ? 1.0 : 0.0},
                {"unfilled_slots", double(unfilled)},
                {"lost_beyond_count", double(lost_beyond_count)},
                {"lost_beyond_capacity", double(lost_beyond_capacity)}};
  return s;
}

std::vector<std::string> DfBuffer::query_sources() const { return {"ldm/dfbuffer/query.glsl"}; }
ShaderDefines DfBuffer::query_defines() const { return query_defines_; }
void DfBuffer::bind_for_query() const {
  offsets_.bind_storage(kBindingOffsets);
  depths_.bind_storage(kBindingDepths);
}

std::vector<BufferMemory> DfBuffer::memory() const {
  const uint64_t stored = stats().fragments_stored;
  const uint64_t scratch = scan_ ? scan_->scratch_bytes() : 0;
  return {{"counts", counts_.bytes(), counts_.bytes()},
          {"offsets", offsets_.bytes(), offsets_.bytes()},
          {"depths", depths_.bytes(), stored * sizeof(float)},
          {"scan_block_sums", scratch, scratch},
          {"counters", counters_.bytes(), counters_.bytes()}};
}

std::vector<std::pair<std::string, std::string>> DfBuffer::sizing() const {
  return {{"depth_capacity_source", size_source(plan_, false)},
          {"depth_capacity", std::to_string(capacity_)},
          {"scan_levels", std::to_string(scan_ ? scan_->levels() : 0)},
          {"sort_local", std::to_string(local_)},
          {"sort_local_policy", sort_local_policy(requested_local_, plan_)}};
}

}  // namespace ldm
