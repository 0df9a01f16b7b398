#pragma once
// The hashed A-buffer (thesis §3.2.13; Lefebvre, Hornus and Lasram 2013): one coherent hash
// table H for all views, keyed by the all-view pixel index p, with h(p, a) = (p + o_a) mod |H|
// and Robin Hood collision resolution by atomicMax on age-and-depth keys, which also sorts
// each pixel's entries by depth during construction. Shaders: shaders/ldm/habuffer/.
//
// Parameters:
//   load_factor=0.75  |H| = max(N * R_LDM^2, ceil(fragments / load_factor)), the fragments
//                     being what the sizing policy knows (ldm_impls/common/sizing.h; under
//                     previous_frame: the entries the last build stored plus those it lost,
//                     counted on the GPU). The lower bound is the age equivalence property
//                     (§3.2.13); above it, the table is sized from what the scene needs.
//                     Under the budget policy |H| = budget (less the age table, offsets and
//                     counters) / key bytes, and load_factor is not used. Lefebvre et al. size tables
//                     somewhat above the fragment count: Robin Hood keeps probe sequences
//                     short up to high loads, and 0.75 (a third more slots than fragments)
//                     trades memory for collisions the usual way. Values > 1 under-size the
//                     table on purpose (it then drops fragments, counted).
//   max_age=254       oldest age an entry may reach (ages 0..max_age; at most 254 since age+1
//                     is stored in 8 bits). A pixel with c fragments needs at least ages
//                     0..c-1, so a smaller cap drops fragments of deep pixels; queries stop at
//                     each pixel's own highest age (the per-pixel age table), so a high cap
//                     costs nothing. Default: the largest the key holds.
//   key_bits=32|64|auto  32 (default, the thesis's choice): 8-bit age and 24-bit quantised
//                     depth (see depth_quantum()), on every device, so that bytes and error
//                     do not change with the device. 64: the exact float depth; needs 64-bit
//                     atomics (GL_NV_shader_atomic_int64 + GL_ARB_gpu_shader_int64). auto:
//                     64 where the device has them, else 32. The record's sizing_key_bits
//                     says which packing ran.
// Sub-passes: clear (table, age table, counters), construct (geometry pass).
//
// previous_frame's first table is a guess (--sizing-initial-per-pixel), often far too small.
// While the table is that guess (and load_factor <= 1), the build runs a variant that stops
// once the table is known to be too small: each fragment takes a ticket, and those from
// T = floor(|H| * load_factor) on store nothing and are counted lost (attempted - T). More
// than T fragments need a table larger than |H| (table_size_for()), so the driver rebuilds
// it anyway, sized from the exact count (stored + dropped + aborted + stopped), and the build
// is judged lossy. Without the stop, the table fills past its load factor to full, and every
// fragment arriving there probes and evicts along up to max_age + 1 slots before one is
// dropped: the first frame cost 17-19 times a steady one (atrium, N 16, R_LDM 128).
// Only the first build runs that variant: the rebuild (after resize()) or, when the guess
// needed no rebuild, the next build leaves the guess for good, so every later build (every
// measured one) runs the unchanged program.
#include <memory>

#include "harness/gl/gl_objects.h"
#include "ldm_impls/common/uint_reduction.h"
#include "ldm_impls/ldm_structure.h"

namespace ldm {

class HaBuffer final : public LdmStructure {
 public:
  explicit HaBuffer(StructureParams& params);
  LDM_STRUCTURE_DECLARATIONS("habuffer");
  void settle_after_first_build() override;
  // 32-bit keys: half the quantisation step (the decoded depth is exact otherwise);
  // 64-bit keys: 0 (the float itself is stored).
  double depth_quantum(const LdmView& view) const override;

 private:
  uint32_t choose_key_bits() const;
  uint64_t table_size_for(const SizingNeeds& needs) const;
  uint64_t fixed_bytes() const;  // everything but the table (for the budget)
  void size_table(uint64_t table_size);
  void allocate_table(uint64_t table_size);
  uint64_t stored_entries() const;      // non-empty table entries (GPU count)
  struct Counters {
    uint64_t dropped = 0, aborted = 0, stopped = 0;  // stopped: from stop_ticket() on, while guessing
    uint64_t lost() const { return dropped + aborted + stopped; }
  };
  Counters read_counters() const;
  void make_counters();
  uint64_t stop_ticket() const;  // while guessing: fragments beyond this many stop
  void leave_guess();
  void upload_offsets();
  uint32_t read_highest_age_count() const;

  double load_factor_ = 0.75;
  uint32_t max_age_ = 254;
  std::string key_bits_request_ = "32";

  SizingPlan plan_;
  uint32_t key_bits_ = 32;
  uint64_t pixels_ = 0;      // N * R_LDM^2
  uint64_t table_size_ = 0;  // |H|, entries
  int depth_step_log2_ = 0;  // 32-bit keys: the quantisation step is 2^depth_step_log2_
  ShaderDefines base_defines_, defines_;
  std::unique_ptr<UintReduction> reduction_;
  const FragmentSource* fragments_ = nullptr;  // from prepare(), for recompiles on resize
  GlBuffer table_, offsets_, age_counts_, counters_, age_summary_;
  GlProgram build_program_, highest_age_program_;
  // previous_frame's guessed first table: builds stop once it must overflow (above).
  bool guessing_ = false;
  bool guess_tried_ = false;  // needed() has read the guessed build's counts
  GlProgram guess_program_;
};

}  // namespace ldm
