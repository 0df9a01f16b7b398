#include "ldm_impls/fixed_arrays/psppfla.h"
#include "ldm_impls/common/sizing_strategy.h"

#include "harness/gl/bindings.h"
#include "ldm_impls/common/structure_counters.h"
#include "ldm_impls/fixed_arrays/ppfla.h"

namespace ldm {

namespace {
// The empty entry: above every ordered depth (shaders/ldm/fixed_arrays/ordered_depth.glsl),
// so that atomicMin stores into it and a pixel's entries end at the first one left empty.
constexpr uint32_t kEmptyEntry = 0xFFFFFFFFu;
}  // namespace

Psppfla::Psppfla(StructureParams& params) : requested_k_(read_fixed_array_k(params)) {}

// A data table of its own counters, alike in form only to the other structures' (see
// ldm_impls/common/structure_counters.h).
std::vector<WorkCounter> Psppfla::work_counters() {
  // shaders/ldm/fixed_arrays/psppfla_build.frag. Every walk ends at the first empty entry it
  // meets and every entry ends exactly one walk, so a pixel of c fragments takes
  // 1 + 2 + ... + min(c, k) atomicMin (plus k per fragment dropped) whatever the order; the
  // entries each fragment shifted depend on the order.
  return with_geometry_counters({"construct"}, {
      {"construct", "atomic_min", WorkShape::Total, "atomics",
       "construct: atomicMin of the insertion walks (one per entry walked)"},
      bytes_loaded("construct", "entries", "array entries read by the atomicMin (4 bytes each)"),
      bytes_stored("construct", "entries",
          "array entries written by the atomicMin (4 bytes each, counted whether or not it "
          "changed the entry)"),
      {"construct", "slots_shifted", WorkShape::Distribution, "entries",
       "construct: entries one fragment's insertion replaced by a nearer depth, each carried on "
       "one slot (one value per fragment)",
       WorkOrder::ArrivalDependent},
      {"construct", "atomic_add", WorkShape::Total, "atomics",
       "construct: atomic counter increments of the fragments dropped beyond k, and (previous_frame "
       "sizing) their atomicAdd on the pixel's overflow count"},
      bytes_loaded("construct", "overflow_counts",
          "overflow counts read by their atomicAdd (previous_frame sizing, a lossy build)"),
      bytes_stored("construct", "overflow_counts",
          "overflow counts written by their atomicAdd (previous_frame sizing, a lossy build)"),
      {"construct", "fragments_dropped", WorkShape::Total, "fragments",
       "construct: fragments beyond their pixel's k entries, dropped (a lossy build)"},
  });
}

// shaders/ldm/fixed_arrays/psppfla_query.glsl; a query is one ldm_begin or ldm_next.
std::vector<WorkCounter> Psppfla::query_work_counters() {
  std::vector<WorkCounter> counters;
  for (WorkCounter c : Ppfla::query_work_counters())
    if (c.name != "bytes_loaded_counts") counters.push_back(std::move(c));  // PSPPFLA has none
  return counters;
}

std::vector<AxisSpec> Psppfla::parameters() { return {fixed_array_k_parameter()}; }

void Psppfla::prepare(const BuildInputs& in) {
  pixels_ = in.views.views().total_pixels();
  dropped_ = GlBuffer("dropped", sizeof(uint32_t));
  size_fixed_ = requested_k_ != 0 || in.sizing.strategy().fixed_by_budget();
  // Only previous_frame asks a build what it needed; the others learn k up front.
  track_overflow_ = !size_fixed_ && in.sizing.strategy().grows_from_counters();
  if (track_overflow_) {
    overflow_ = GlBuffer("overflow_counts", pixels_ * sizeof(uint32_t));
    overflow_.clear_to_zero();
  }
  fragments_ = &in.fragments;
  if (!reduction_) reduction_ = std::make_unique<UintReduction>();
  allocate(plan_fixed_arrays("psppfla", requested_k_, in, dropped_.bytes()));
}

void Psppfla::allocate(const FixedArrayLayout& layout) {
  layout_ = layout;
  defines_ = fixed_array_defines(layout_);
  entries_ = GlBuffer("entries", layout_.entry_bytes());
  ShaderDefines build_defines = defines_;
  build_defines.set("FA_TRACK_OVERFLOW", track_overflow_ ? 1 : 0);
  build_program_ = fragments_->build_program("ldm/fixed_arrays/psppfla_build.frag", build_defines);
  query_defines_changed();
}

SizingNeeds Psppfla::needed() {
  if (read_dropped(dropped_) == 0) return {0, layout_.k};
  if (!track_overflow_)  // a fixed k (parameter, budget) or a policy that sizes up front
    return {0, layout_.k + 1, true};
  // Cleared only after a build that dropped something, so steady state costs nothing.
  const uint32_t most_dropped = reduction_->run(overflow_, pixels_).max;
  overflow_.clear_to_zero();
  return {0, layout_.k + most_dropped, true};
}

bool Psppfla::fits(const SizingNeeds& needs) const {
  return size_fixed_ || k_for(needs, pixels_) <= layout_.k;
}

void Psppfla::resize(const SizingNeeds& needs) {
  if (!fits(needs)) allocate(resized_fixed_arrays("psppfla", layout_, k_for(needs, pixels_)));
}

void Psppfla::build(const BuildInputs& in, GpuTimer* timer) {
  {
    ScopedSubpass timed(timer, "clear");
    entries_.clear_to_uint(kEmptyEntry);
    dropped_.clear_to_zero();
  }
  {
    ScopedSubpass timed(timer, "construct");
    entries_.bind_storage(kStructureBinding0);
    if (track_overflow_) overflow_.bind_storage(kStructureBinding0 + 1);
    dropped_.bind_atomic_counter(kStructureCounterBinding);
    in.fragments.run(build_program_);
  }
}

BuildStats Psppfla::stats() const {
  // The entries holding a depth (a GPU count, untimed) plus the fragments dropped.
  const uint64_t dropped = read_dropped(dropped_);
  const uint64_t filled = reduction_->run(entries_, layout_.entries(), 1, kEmptyEntry).nonempty;
  BuildStats s = fixed_array_stats(filled + dropped, dropped);
  return s;
}

std::vector<std::string> Psppfla::query_sources() const {
  return {"ldm/fixed_arrays/psppfla_query.glsl"};
}
ShaderDefines Psppfla::query_defines() const { return defines_; }
void Psppfla::bind_for_query() const { entries_.bind_storage(kStructureBinding0); }

std::vector<BufferMemory> Psppfla::memory() const {
  const uint64_t stored = stats().fragments_stored;
  std::vector<BufferMemory> m = {{"entries", entries_.bytes(), stored * sizeof(uint32_t)},
                                 {"dropped_counter", dropped_.bytes(), dropped_.bytes()}};
  if (track_overflow_) m.push_back({"overflow_counts", overflow_.bytes(), overflow_.bytes()});
  return m;
}

std::vector<std::pair<std::string, std::string>> Psppfla::sizing() const {
  return fixed_array_sizing(layout_);
}

}  // namespace ldm
