#include "ldm_impls/fixed_arrays/ppfla.h"
#include "ldm_impls/common/sizing_strategy.h"

#include <algorithm>

#include "harness/gl/bindings.h"
#include "ldm_impls/common/compute_grid.h"
#include "ldm_impls/common/post_sort.h"
#include "ldm_impls/common/structure_counters.h"

namespace ldm {

Ppfla::Ppfla(StructureParams& params) : requested_k_(read_fixed_array_k(params)) {}

// A data table of its own counters, alike in form only to the other structures' (see
// ldm_impls/common/structure_counters.h).
std::vector<WorkCounter> Ppfla::work_counters() {
  return with_geometry_counters({"construct"}, {
      // shaders/ldm/fixed_arrays/ppfla_build.frag: which entry a fragment takes depends on
      // the order they arrive, how many each pixel fills does not.
      {"construct", "atomic_add", WorkShape::Total, "atomics",
       "construct: atomicAdd on a pixel's count (one per fragment) and atomic counter increments "
       "of the fragments dropped beyond k"},
      bytes_loaded("construct", "counts", "counts read (the atomicAdd's read, 4 bytes per fragment)"),
      bytes_stored("construct", "counts", "counts written (the atomicAdd's write, 4 bytes per fragment)"),
      bytes_stored("construct", "entries", "array entries written (4 bytes per fragment stored)"),
      {"construct", "fragments_dropped", WorkShape::Total, "fragments",
       "construct: fragments beyond their pixel's k entries, dropped (a lossy build)"},
      // shaders/ldm/fixed_arrays/ppfla_sort.comp with ldm/common/heap_sort.glsl: the heap
      // sort's steps depend on the order the construct left the entries in.
      sort_invocations_counter(),
      {"sort", "list_length", WorkShape::Distribution, "entries",
       "sort: entries a pixel's sort ordered (min(count, k); one value per pixel, empty ones "
       "included)"},
      bytes_loaded("sort", "counts", "counts read (4 bytes per pixel)"),
      bytes_loaded("sort", "entries", "array entries the heap sort read (4 bytes each)", kArrival),
      bytes_stored("sort", "entries", "array entries the heap sort wrote (4 bytes each)", kArrival),
      {"sort", "comparisons", WorkShape::Total, "comparisons",
       "sort: depth comparisons of the heap sort (ldm/common/heap_sort.glsl)", kArrival},
      {"sort", "moves", WorkShape::Total, "moves",
       "sort: entries the heap sort moved (ldm/common/heap_sort.glsl)", kArrival},
  });
}

// shaders/ldm/fixed_arrays/ppfla_query.glsl; a query is one ldm_begin or ldm_next. The sorted
// arrays are the same whatever the order of arrival, so their reads are deterministic.
std::vector<WorkCounter> Ppfla::query_work_counters() {
  return {
      {"", "slots_scanned", WorkShape::Distribution, "slots",
       "array slots one query of PPFLA or PSPPFLA (an ldm_begin or ldm_next) moved to or read to "
       "find the pixel's next entry: 1, or 0 past the last (PPFLA, whose count tells where its "
       "entries end; PSPPFLA reads the empty entry after its last and scans 0 only past k)"},
      bytes_loaded("", "counts", "PPFLA counts its queries read (one per ldm_begin)"),
      bytes_loaded("", "entries", "PPFLA or PSPPFLA array entries its queries read (4 bytes each)"),
  };
}

std::vector<AxisSpec> Ppfla::parameters() { return {fixed_array_k_parameter()}; }

void Ppfla::prepare(const BuildInputs& in) {
  pixels_ = in.views.views().total_pixels();
  counts_ = GlBuffer("counts", pixels_ * sizeof(uint32_t));
  dropped_ = GlBuffer("dropped", sizeof(uint32_t));
  size_fixed_ = requested_k_ != 0 || in.sizing.strategy().fixed_by_budget();
  fragments_ = &in.fragments;
  if (!reduction_) reduction_ = std::make_unique<UintReduction>();
  allocate(plan_fixed_arrays("ppfla", requested_k_, in, counts_.bytes() + dropped_.bytes()));
}

void Ppfla::allocate(const FixedArrayLayout& layout) {
  layout_ = layout;
  defines_ = fixed_array_defines(layout_);
  entries_ = GlBuffer("entries", layout_.entry_bytes());
  build_program_ = fragments_->build_program("ldm/fixed_arrays/ppfla_build.frag", defines_);
  sort_program_ = build_compute_program("ldm/fixed_arrays/ppfla_sort.comp", defines_);
  query_defines_changed();
}

SizingNeeds Ppfla::needed() {
  // A pixel's count keeps counting past k, so its deepest count is the k the build needed;
  // reduced on the GPU only when something was dropped (else k sufficed).
  if (read_dropped(dropped_) == 0) return {0, layout_.k};
  return {0, reduction_->run(counts_, pixels_).max, true};
}

bool Ppfla::fits(const SizingNeeds& needs) const {
  return size_fixed_ || k_for(needs, pixels_) <= layout_.k;
}

void Ppfla::resize(const SizingNeeds& needs) {
  if (!fits(needs)) allocate(resized_fixed_arrays("ppfla", layout_, k_for(needs, pixels_)));
}

void Ppfla::bind_storage() const {
  entries_.bind_storage(kStructureBinding0);
  counts_.bind_storage(kStructureBinding0 + 1);
}

void Ppfla::sort_every_pixel() const {
  bind_storage();
  // One invocation per pixel in groups of 64 (local_size_x of ppfla_sort.comp).
  run_linear_compute(sort_program_, layout_.pixels, 64,
                     GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
}

void Ppfla::build(const BuildInputs& in, GpuTimer* timer) {
  {
    // Entries need no clearing: a pixel's count says how many of them this build wrote.
    ScopedSubpass timed(timer, "clear");
    counts_.clear_to_zero();
    dropped_.clear_to_zero();
  }
  {
    ScopedSubpass timed(timer, "construct");
    bind_storage();
    dropped_.bind_atomic_counter(kStructureCounterBinding);
    in.fragments.run(build_program_);
  }
  {
    ScopedSubpass timed(timer, "sort");
    sort_every_pixel();
  }
}

BuildStats Ppfla::stats() const {
  // Every fragment incremented its pixel's count, stored or not.
  const uint64_t rasterized = reduction_->run(counts_, pixels_).sum;
  BuildStats s = fixed_array_stats(rasterized, read_dropped(dropped_));
  return s;
}

std::vector<std::string> Ppfla::query_sources() const {
  return {"ldm/fixed_arrays/ppfla_query.glsl"};
}
ShaderDefines Ppfla::query_defines() const { return defines_; }
void Ppfla::bind_for_query() const { bind_storage(); }

std::vector<BufferMemory> Ppfla::memory() const {
  const uint64_t stored = stats().fragments_stored;
  return {{"entries", entries_.bytes(), stored * sizeof(uint32_t)},
          {"counts", counts_.bytes(), counts_.bytes()},
          {"dropped_counter", dropped_.bytes(), dropped_.bytes()}};
}

std::vector<std::pair<std::string, std::string>> Ppfla::sizing() const {
  return fixed_array_sizing(layout_);
}

}  // namespace ldm
