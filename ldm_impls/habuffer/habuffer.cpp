#include "ldm_impls/habuffer/habuffer.h"
#include "ldm_impls/common/sizing_strategy.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "harness/gl/bindings.h"
#include "harness/util/error.h"
#include "harness/util/text.h"
#include "ldm_impls/common/compute_grid.h"
#include "ldm_impls/common/structure_counters.h"
#include "ldm_impls/common/uint_reduction.h"

namespace ldm {

namespace {

// 2^24 - 1: the largest value of the 24-bit depth field of 32-bit keys.
constexpr double kQuantisedDepthMax = 16777215.0;
// The offsets o_a are fixed for reproducible builds (the same |H| gives the same table).
constexpr uint64_t kOffsetSeed = 0x4861427566666572ull;  // "HaBuffer"
constexpr uint32_t kCounterWords = 2;                    // dropped at max age, aborted insertions
// While the table is previous_frame's guess, a third word: fragments attempted.
constexpr uint32_t kGuessCounterWords = 3;

bool gl_extension_present(const char* name) {
  GLint count = 0;
  glGetIntegerv(GL_NUM_EXTENSIONS, &count);
  for (GLint i = 0; i < count; ++i) {
    const char* ext = reinterpret_cast<const char*>(glGetStringi(GL_EXTENSIONS, GLuint(i)));
    if (ext && std::string(ext) == name) return true;
  }
  return false;
}

// 64-bit atomicMax on buffer variables, and the 64-bit integer type it works on.
bool device_has_int64_atomics() {
  return gl_extension_present("GL_NV_shader_atomic_int64") &&
         gl_extension_present("GL_ARB_gpu_shader_int64");
}

std::string gl_renderer() {
  const char* renderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
  return renderer ? renderer : "unknown renderer";
}

// The smallest e with 2^e * (2^24 - 1) >= every view's depth range: 32-bit keys quantise on
// the step 2^e so that every depth in [0, depth_range] fits 24 bits and both quantising and
// decoding are exact float operations (ha_keys.glsl).
int quantisation_step_log2(const ViewSet& views) {
  double range = 1e-30;
  for (const LdmView& v : views.views) range = std::max(range, double(v.depth_range));
  int e = int(std::ceil(std::log2(range / kQuantisedDepthMax)));
  while (std::ldexp(kQuantisedDepthMax, e) < range) ++e;
  while (std::ldexp(kQuantisedDepthMax, e - 1) >= range) --e;
  return e;
}

uint64_t splitmix64(uint64_t& state) {
  uint64_t z = (state += 0x9E3779B97F4A7C15ull);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

// o_0 .. o_{count-1}, pseudo-random in [0, table_size), distinct when the table allows it (two
// equal offsets would make two ages of one pixel share a slot).
std::vector<uint32_t> make_offsets(uint64_t table_size, uint32_t count) {
  uint64_t state = kOffsetSeed;
  std::vector<uint32_t> offsets;
  while (offsets.size() < count) {
    const uint32_t offset = uint32_t(splitmix64(state) % table_size);
    if (table_size < count || std::find(offsets.begin(), offsets.end(), offset) == offsets.end())
      offsets.push_back(offset);
  }
  return offsets;
}

}  // namespace

HaBuffer::HaBuffer(StructureParams& params) {
  load_factor_ = params.get_double("load_factor");
  max_age_ = uint32_t(params.get_uint("max_age"));
  key_bits_request_ = params.get_choice("key_bits");
}

// A data table of its own counters, alike in form only to the other structures' (see
// ldm_impls/common/structure_counters.h).
std::vector<WorkCounter> HaBuffer::work_counters() {
  // Counted by shaders/ldm/habuffer/ha_build.frag, once per fragment. Every insertion chain
  // depends on what arrived before it (which entry an atomicMax finds), so all but the
  // tickets are arrival-dependent; the table they end in is not (see query_work_counters()).
  return with_geometry_counters({"construct"}, {
      {"construct", "hash_probes", WorkShape::Distribution, "slots",
       "construct: slots one fragment's insertion tried (an atomicMax on the table each), "
       "evicted entries carried on included", kArrival},
      {"construct", "atomic_max", WorkShape::Total, "atomics",
       "construct: 32-bit atomicMax: on the table (32-bit keys) and on the age table (one per "
       "placement)", kArrival},
      {"construct", "atomic_max_64", WorkShape::Total, "atomics",
       "construct: 64-bit atomicMax on the table (key_bits=64 only; 0 with 32-bit keys)", kArrival},
      {"construct", "atomic_max_failed", WorkShape::Total, "atomics",
       "construct: atomicMax on the table that left the slot's key (an older entry, the same "
       "pixel's nearer fragment, or an equal key): the carried entry moves on unchanged", kArrival},
      {"construct", "evictions", WorkShape::Total, "entries",
       "construct: entries a carried entry took the slot of (Robin Hood), carried on in its place", kArrival},
      {"construct", "age_bumps", WorkShape::Total, "steps",
       "construct: times a carried entry aged by one to try its next slot", kArrival},
      {"construct", "atomic_add", WorkShape::Total, "atomics",
       "construct: atomic counter increments of the ticket each fragment takes while "
       "previous_frame's first guess is built (else 0)"},
      {"construct", "atomic_add_on_loss", WorkShape::Total, "atomics",
       "construct: atomic counter increments of insertions dropped at max_age or aborted (a "
       "lossy HA-buffer build only)", kArrival},
      bytes_loaded("construct", "table", "table bytes read by the atomicMax (key_bits / 8 each)", kArrival),
      bytes_stored("construct", "table",
          "table bytes written by the atomicMax (key_bits / 8 each, counted whether or "
          "not it changed the key)", kArrival),
      bytes_loaded("construct", "age_table",
          "age table bytes read by the atomicMax of each placement", kArrival),
      bytes_stored("construct", "age_table",
          "age table bytes written by the atomicMax of each placement", kArrival),
      bytes_loaded("construct", "ha_offsets",
          "offsets o_a read: one per slot tried, one per eviction (the evicted entry's pixel)", kArrival),
  });
}

// Counted by shaders/ldm/habuffer/ha_query.glsl; a query is one ldm_begin or ldm_next. Robin
// Hood by age is history independent: at a slot the older entry wins, and two entries of one
// age at one slot belong to one pixel, so which slots each pixel's entries end in depends only
// on how many fragments each pixel has (the order of one pixel's own entries is by depth),
// never on the order they arrived. The probes are therefore deterministic; a model of the
// insertions under random interleavings, tables that drop entries at max_age included, always
// ends in one table (tests/work/hash_and_array_work_test.cpp).
std::vector<WorkCounter> HaBuffer::query_work_counters() {
  return {
      {"", "hash_probes", WorkShape::Distribution, "slots",
       "slots one query of the HA-buffer read (an ldm_begin or ldm_next seeking the pixel's next "
       "entry; 0 past its last); slots of other pixels' entries are skipped"},
      bytes_loaded("", "table", "HA-buffer table bytes its queries read"),
      bytes_loaded("", "ha_offsets", "HA-buffer offsets o_a its queries read (one per probe)"),
      bytes_loaded("", "age_table", "HA-buffer age table bytes its queries read (one word per ldm_begin)"),
  };
}

std::vector<AxisSpec> HaBuffer::parameters() {
  AxisSpec load_factor = numeric_parameter("load_factor", AxisKind::Real, 0.01, 64.0, "0.75",
                                           "fragments per entry",
                                           "table size |H| = max(N R^2, fragments / load_factor)");
  load_factor.real_is_double = true;
  const AxisSpec max_age = numeric_parameter(
      "max_age", AxisKind::UInt, 0, 254, "254", "probes",
      "longest probe sequence; fragments that would need more are dropped and counted");
  // 32 by default on every device: the records of two devices then compare the same packing.
  const AxisSpec key_bits = choice_parameter(
      "key_bits", {"32", "64", "auto"}, "32",
      "key packing: 32 (8-bit age, 24-bit depth), 64 (the exact float; needs 64-bit atomics), auto");
  return {load_factor, max_age, key_bits};
}

uint32_t HaBuffer::choose_key_bits() const {
  const bool has_int64_atomics = device_has_int64_atomics();
  if (key_bits_request_ == "64" && !has_int64_atomics)
    throw UserError(
        "habuffer parameter key_bits=64 needs 64-bit atomics "
        "(GL_NV_shader_atomic_int64 and GL_ARB_gpu_shader_int64), which " +
        gl_renderer() + " lacks; use key_bits=32 or key_bits=auto");
  if (key_bits_request_ == "32") return 32;
  return has_int64_atomics ? 64 : 32;
}

uint64_t HaBuffer::table_size_for(const SizingNeeds& needs) const {
  const double wanted = std::ceil(double(needs.fragments) / load_factor_);
  // |H| >= N * R_LDM^2 keeps p = (h - o_a) mod |H| unique: the age equivalence property.
  return std::max<uint64_t>({pixels_, uint64_t(wanted), 1});
}

uint64_t HaBuffer::fixed_bytes() const {
  return pixels_ * sizeof(uint32_t) + kCounterWords * sizeof(uint32_t) + sizeof(uint32_t) +
         (max_age_ + 1) * sizeof(uint32_t);
}

void HaBuffer::size_table(uint64_t table_size) {
  table_size_ = table_size;
  // h = p + o_a with p, o_a < |H| must not wrap 32 bits.
  if (table_size_ >= (uint64_t(1) << 31))
    throw UserError("habuffer: a table of " + std::to_string(table_size_) +
                    " entries is beyond 32-bit hashing; raise load_factor or lower N or R_LDM");
}

void HaBuffer::upload_offsets() {
  const std::vector<uint32_t> offsets = make_offsets(table_size_, max_age_ + 1);
  offsets_ = GlBuffer("offsets", offsets.size() * sizeof(uint32_t), offsets.data());
}

void HaBuffer::prepare(const BuildInputs& in) {
  plan_ = in.sizing;
  key_bits_ = choose_key_bits();
  pixels_ = in.views.views().total_pixels();
  depth_step_log2_ = quantisation_step_log2(in.views.views());
  age_counts_ = GlBuffer("age_table", pixels_ * sizeof(uint32_t));
  // A table sized from a guess, which an overflow makes the driver rebuild from its counts.
  guessing_ = plan_.strategy().grows_from_counters() && !plan_.strategy().fixed_by_budget() &&
              load_factor_ <= 1.0;
  make_counters();
  age_summary_ = GlBuffer("age_summary", sizeof(uint32_t));
  fragments_ = &in.fragments;
  base_defines_ = common_structure_defines(in);
  if (plan_.strategy().fixed_by_budget()) {
    const uint64_t entries = budget_after("habuffer", plan_, fixed_bytes()) / (key_bits_ / 8);
    if (entries < pixels_)
      throw UserError("habuffer: the sizing budget holds " + std::to_string(entries) +
                      " table entries, fewer than the " + std::to_string(pixels_) +
                      " LDM pixels that age equivalence needs; raise --sizing-budget-mib");
    allocate_table(entries);
  } else {
    allocate_table(table_size_for(plan_.initial));
  }
}

SizingNeeds HaBuffer::needed() {
  // Every fragment ends stored in one entry, dropped at max age, aborted or (while guessing)
  // stopped beyond what the table is sized for; the entries are counted on the GPU, so this is what the table
  // had to hold even when it overflowed.
  const uint64_t lost = read_counters().lost();
  const SizingNeeds needs{stored_entries() + lost, 0, lost > 0};
  // The guess has had its one build: a rebuild (resize()) or the next build leaves it (not
  // here: this frame's stats() still reads the counters the guessed build wrote).
  if (guessing_) guess_tried_ = true;
  return needs;
}

bool HaBuffer::fits(const SizingNeeds& needs) const {
  return plan_.strategy().fixed_by_budget() || table_size_for(needs) <= table_size_;
}

void HaBuffer::resize(const SizingNeeds& needs) {
  if (fits(needs)) return;
  if (guessing_) leave_guess();  // sized from counts from now on
  allocate_table(table_size_for(needs));
}

void HaBuffer::settle_after_first_build() {
  if (guessing_) leave_guess();  // as build() does once the guess has had its one build
}

uint64_t HaBuffer::stop_ticket() const {
  // More fragments than |H| * load_factor need a table larger than |H| (table_size_for()), so
  // with load_factor <= 1 a build that reaches this many is rebuilt whatever it stores.
  return std::max<uint64_t>(1, uint64_t(std::floor(double(table_size_) * load_factor_)));
}

void HaBuffer::make_counters() {
  const std::vector<uint32_t> zero(guessing_ ? kGuessCounterWords : kCounterWords, 0u);
  counters_ = GlBuffer("counters", zero.size() * sizeof(uint32_t), zero.data());
}

void HaBuffer::leave_guess() {
  guessing_ = false;
  guess_program_ = GlProgram();
  make_counters();
}

uint64_t HaBuffer::stored_entries() const {
  return reduction_->run(table_, table_size_, key_bits_ / 32).nonempty;
}

HaBuffer::Counters HaBuffer::read_counters() const {
  uint32_t words[kGuessCounterWords] = {0, 0, 0};
  counters_.download(words, guessing_ ? kGuessCounterWords * sizeof(uint32_t)
                                      : kCounterWords * sizeof(uint32_t));
  Counters c;
  c.dropped = words[0];
  c.aborted = words[1];
  // Tickets from stop_ticket() on stored nothing: exactly attempted - stop_ticket() fragments.
  if (guessing_ && words[2] > stop_ticket()) c.stopped = words[2] - stop_ticket();
  return c;
}

void HaBuffer::allocate_table(uint64_t table_size) {
  size_table(table_size);
  const uint64_t key_bytes = key_bits_ / 8;
  table_ = GlBuffer("table", checked_storage_block("habuffer", "table", table_size_ * key_bytes));
  upload_offsets();
  if (!reduction_) reduction_ = std::make_unique<UintReduction>();

  defines_ = base_defines_;
  defines_.set("HA_KEY_BITS", key_bits_);
  defines_.set("HA_TABLE_SIZE", std::to_string(table_size_) + "u");
  defines_.set("HA_MAX_AGE", std::to_string(max_age_) + "u");
  defines_.set("HA_DEPTH_STEP_LOG2", depth_step_log2_);
  // Each step ages the carried entry by one; a chain longer than 64 full age ranges would
  // mean a faulty device (see ha_build.frag).
  defines_.set("HA_MAX_INSERT_STEPS", std::to_string(64ull * (max_age_ + 1)) + "u");

  ShaderDefines build_defines = defines_;
  build_defines.set("HA_STOP_WHEN_FULL", 0);
  build_program_ = fragments_->build_program("ldm/habuffer/ha_build.frag", build_defines);
  if (guessing_) {
    ShaderDefines guess_defines = defines_;
    guess_defines.set("HA_STOP_WHEN_FULL", 1);
    guess_defines.set("HA_STOP_TICKET", std::to_string(stop_ticket()) + "u");
    guess_program_ = fragments_->build_program("ldm/habuffer/ha_build.frag", guess_defines);
  }
  highest_age_program_ = build_compute_program("ldm/habuffer/ha_highest_age.comp", defines_);
  query_defines_changed();
}

void HaBuffer::build(const BuildInputs& in, GpuTimer* timer) {
  if (guessing_ && guess_tried_) leave_guess();  // the guess held (or held enough): plain program
  {
    ScopedSubpass timed(timer, "clear");
    table_.clear_to_zero();  // key 0: empty, below every key with an age
    age_counts_.clear_to_zero();
    counters_.clear_to_zero();
  }
  {
    ScopedSubpass timed(timer, "construct");
    bind_for_query();
    age_counts_.bind_storage(kStructureBinding0 + 2);
    counters_.bind_atomic_counter(kStructureCounterBinding);
    in.fragments.run(guessing_ ? guess_program_ : build_program_);
  }
}

uint32_t HaBuffer::read_highest_age_count() const {
  // A scratch word of the read-back, not state of the structure: cleared here directly.
  const uint32_t zero = 0;
  glClearNamedBufferData(age_summary_.id(), GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
  age_counts_.bind_storage(kStructureBinding0 + 2);
  age_summary_.bind_storage(kStructureBinding0 + 3);
  run_linear_compute(highest_age_program_, pixels_, 256, GL_BUFFER_UPDATE_BARRIER_BIT);
  uint32_t highest = 0;
  age_summary_.download(&highest, sizeof highest);
  return highest;
}

BuildStats HaBuffer::stats() const {
  const Counters counters = read_counters();
  const uint64_t dropped = counters.dropped, aborted = counters.aborted;
  const uint32_t highest_age_count = read_highest_age_count();
  BuildStats s;
  // Entries found in the table (a GPU count, untimed) plus the fragments counted as lost.
  s.fragments_stored = stored_entries();
  s.fragments_lost = counters.lost();
  s.fragments_rasterized = s.fragments_stored + s.fragments_lost;
  s.overflow = s.fragments_lost > 0;
  s.counters = {{"max_age_used", highest_age_count ? double(highest_age_count - 1) : 0.0},
                {"dropped_max_age", double(dropped)},
                {"aborted_insertions", double(aborted)}};
  // Only a build from previous_frame's guess can stop early (a measured build never does).
  if (guessing_) s.counters.emplace_back("stopped_table_too_small", double(counters.stopped));
  return s;
}

std::vector<std::string> HaBuffer::query_sources() const { return {"ldm/habuffer/ha_query.glsl"}; }
ShaderDefines HaBuffer::query_defines() const { return defines_; }

void HaBuffer::bind_for_query() const {
  table_.bind_storage(kStructureBinding0);
  offsets_.bind_storage(kStructureBinding0 + 1);
  age_counts_.bind_storage(kStructureBinding0 + 2);
}

std::vector<BufferMemory> HaBuffer::memory() const {
  const uint64_t stored = stats().fragments_stored;
  const uint64_t key_bytes = key_bits_ / 8;
  return {{"table", table_.bytes(), stored * key_bytes},
          {"age_table", age_counts_.bytes(), age_counts_.bytes()},
          {"offsets", offsets_.bytes(), offsets_.bytes()},
          {"counters", counters_.bytes(), counters_.bytes()}};
}

std::vector<std::pair<std::string, std::string>> HaBuffer::sizing() const {
  std::vector<std::pair<std::string, std::string>> s = {
      {"table_entries", std::to_string(table_size_)},
      {"table_size_source", size_source(plan_, false)},
      {"table_policy", plan_.strategy().fixed_by_budget()
                           ? "budget / key bytes"
                           : "max(N*R_LDM^2, ceil(fragments / load_factor))"},
      {"load_factor", format_significant(load_factor_, 4)},
      {"load_factor_actual", format_significant(double(stats().fragments_rasterized) / double(table_size_), 4)},
      {"max_age", std::to_string(max_age_)},
      {"key_bits", std::to_string(key_bits_)},
      {"key_bits_request", key_bits_request_}};
  if (key_bits_ == 32)
    s.emplace_back("depth_step", format_significant(std::ldexp(1.0, depth_step_log2_), 4));
  return s;
}

double HaBuffer::depth_quantum(const LdmView& view) const {
  (void)view;  // one step for all views: the largest depth range fixes it
  return key_bits_ == 64 ? 0.0 : 0.5 * std::ldexp(1.0, depth_step_log2_);
}

}  // namespace ldm
